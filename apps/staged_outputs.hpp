#pragma once
// The outputs of a run: checked before any rendering, then written to new temporary files beside
// their targets and renamed into place together, only when all were written; a second stop
// signal removes the temporaries (stop_signals.hpp).

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/io/image_writer.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// Checks every output of the run before any rendering (throws ImageWriteError) and returns the
/// PNG's path.
std::string check_outputs(const Options& options);

/// A file to write: its target and what writes its content into the temporary (write() or
/// append() then finish()).
struct StagedOutput {
  std::filesystem::path path;
  std::function<void(glint::StagedFile&)> write;
};

/// Writes every file to a new temporary file, then renames them all into place only when all
/// were written; on any failure, or a second signal, no temporary is left.
void write_staged(const std::vector<StagedOutput>& outputs);

/// The checkpoint as a StagedOutput, encoded piece by piece into its temporary: never a copy of
/// the sums (24 bytes a pixel) in memory.
StagedOutput checkpoint_output(const std::string& path, const glint::CheckpointKey& key,
                               int passes_done, int samples_per_pixel_done,
                               const glint::PixelSums& sums);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
