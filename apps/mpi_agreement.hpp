#pragma once
// glint-render-mpi's ranks agreeing before the render: on whether a step failed anywhere (one
// message, one status for all), and on rendering the same image.

#include <optional>
#include <string_view>

#include "failure.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"
#include "mpi_world.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

/// Every rank says whether its step failed; when one did, rank 0 prints one message (its own,
/// or else the first failing rank's) and every rank gets the status to exit with (0: go on).
/// So a scene error that every rank meets is printed once.
int agree(const World& world, const std::optional<cli::Failure>& mine);

/// Runs a step on this rank, catching its failure for agree().
template <typename Step>
std::optional<cli::Failure> attempt(const Program& program, const Step& step) {
  try {
    step();
    return std::nullopt;
  } catch (...) {
    return cli::current_failure(program);
  }
}

/// Throws unless this rank renders the image rank 0 renders: the same --estimator (`estimator`:
/// its name, or auto), variant and execution model and every setting that changes the image
/// (the thread count does not), naming the first difference. Every rank's work goes into one
/// image, so ranks started with different options (mpirun's A : B form) would otherwise mix two
/// renders into one. The scene's bytes are agreed on elsewhere (rank 0 sends them, or
/// --scene-everywhere compares their hashes).
void check_same_image(const Program& program, const Options& options,
                      const glint::RenderSettings& settings, std::string_view estimator);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
