// staged_outputs.hpp's definitions: the outputs' checks and their staged writing.

#include "staged_outputs.hpp"

#include <optional>
#include <system_error>

#include "glint/error.hpp"
#include "stop_signals.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

namespace {

/// Refuses, before any rendering, an output that cannot be written or would destroy the scene.
void check_output(const std::string& output, const std::string& scene) {
  glint::check_output_path(output);
  std::error_code error;
  if (std::filesystem::equivalent(output, scene, error))
    throw glint::ImageWriteError("cannot write " + output + ": it is the scene file " + scene);
}

/// Forgets the temporaries the handler would remove, when the files themselves are gone or
/// renamed (declared before them, it runs after their removal).
struct ForgetTemporaries {
  ~ForgetTemporaries() { forget_temporaries(); }
};

}  // namespace

void write_staged(const std::vector<StagedOutput>& outputs) {
  const ForgetTemporaries forget;
  std::vector<glint::StagedFile> staged;
  staged.reserve(outputs.size());
  {
    const BlockStopSignals block;
    for (const StagedOutput& output : outputs) {
      staged.emplace_back(output.path);
      if (!note_temporary(staged.back().temporary().native()))
        throw glint::ImageWriteError("cannot write " + output.path.string() + ": path too long");
    }
  }
  for (std::size_t i = 0; i < outputs.size(); ++i)
    outputs[i].write(staged[i]);
  const BlockStopSignals block;
  for (glint::StagedFile& file : staged)
    file.commit();
}

StagedOutput checkpoint_output(const std::string& path, const glint::CheckpointKey& key,
                               int passes_done, int samples_per_pixel_done,
                               const glint::PixelSums& sums) {
  return {path, [&key, passes_done, samples_per_pixel_done, &sums](glint::StagedFile& file) {
            glint::encode_checkpoint_pieces(
                key, passes_done, samples_per_pixel_done, sums,
                [&](const char* data, std::size_t size) { file.append(data, size); });
            file.finish();
          }};
}

std::string check_outputs(const Options& options) {
  const std::string output = options.output
                                 ? *options.output
                                 : std::filesystem::path(options.scene).stem().string() + ".png";
  check_output(output, options.scene);
  if (options.hdr) check_output(*options.hdr, options.scene);
  if (options.exr) check_output(*options.exr, options.scene);
  if (options.stats_json) check_output(*options.stats_json, options.scene);
  if (options.checkpoint) {
    check_output(*options.checkpoint, options.scene);
    // The files are renamed into place together: one would silently replace the other.
    const auto resolved = [](const std::string& path) {
      return std::filesystem::weakly_canonical(std::filesystem::absolute(path));
    };
    for (const std::optional<std::string>& image :
         {std::optional(output), options.hdr, options.exr})
      if (image && resolved(*image) == resolved(*options.checkpoint))
        throw glint::ImageWriteError("cannot write the checkpoint " + *options.checkpoint +
                                     ": it is also the image " + *image);
    if (options.stats_json && resolved(*options.stats_json) == resolved(*options.checkpoint))
      throw glint::ImageWriteError("cannot write the checkpoint " + *options.checkpoint +
                                   ": it is also the --stats-json file");
    // A checkpoint is replaced only by the render it holds, continued: a run repeated without
    // --resume would replace the passes of hours with those of minutes.
    std::error_code error;
    const std::string& file = *options.checkpoint;
    if (std::filesystem::exists(std::filesystem::symlink_status(file, error)) &&
        !(options.resume && std::filesystem::equivalent(*options.resume, file, error)))
      throw glint::ImageWriteError("cannot write the checkpoint " + file +
                                   ": it exists, and may hold more of the render than this run "
                                   "will: continue it with --resume " +
                                   file + ", or remove it to start again");
  }
  // What a run killed while writing (kill -9 during a checkpoint) left beside the targets.
  for (const std::optional<std::string>& target :
       {std::optional(output), options.hdr, options.exr, options.stats_json, options.checkpoint})
    if (target) glint::remove_stale_temporaries(*target);
  return output;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
