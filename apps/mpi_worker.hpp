#pragma once
// A rank of glint-render-mpi other than 0: it renders the tiles rank 0 assigns, sending back
// each finished tile's sums with its next request, and its splats after each pass, until told
// to stop.

#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"
#include "mpi_rank_renderer.hpp"
#include "mpi_world.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi {

/// A rank other than 0: renders what rank 0 assigns until told to stop, into `sums` with
/// `renderer`'s `threads` threads, then sends rank 0 its report. A failure here ends the run.
void serve(const World& world, const glint::RenderSettings& settings, RankRenderer& renderer,
           glint::PixelSums& sums, int threads);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli::mpi
