#pragma once
// Between the passes of a render: the checkpoints of a run (their key, the one resumed, the one
// written every --checkpoint-interval seconds and at the end) and --time-limit.

#include <cstdint>
#include <optional>
#include <string>

#include "glint/image/pixel_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/checkpoint.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/render/renderer.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

/// The checkpoints of a run: the key its checkpoints carry, the checkpoint it resumes, and, kept
/// by the pass callback, the count of the last completed pass for the checkpoint written at the
/// end (whatever stops the render after it) from the render's own sums. Between passes it writes a
/// checkpoint every
/// --checkpoint-interval seconds and applies --time-limit.
class PassKeeper {
 public:
  /// `scene_hash`: scene_text_hash of the scene file's text, needed only when a checkpoint is
  /// written or resumed. `resumed`: --resume's checkpoint where the program has read it already
  /// (read_resumed), else it is read here. Throws CheckpointError for a checkpoint that cannot be
  /// resumed.
  PassKeeper(const Program& program, const Options& options, const glint::RenderSettings& settings,
             std::uint64_t scene_hash, std::optional<glint::Checkpoint> resumed = std::nullopt);

  /// --resume's checkpoint, read (none without --resume): for a program that needs to know what
  /// made it before it chooses its variant. Throws CheckpointError.
  static std::optional<glint::Checkpoint> read_resumed(const Options& options);

  /// The variant that made checkpoint `c`: its key's name, less the ", wavefront" with which
  /// older checkpoints of the wavefront renderer name it (their sums are the scalar renderer's).
  static std::string made_by(const glint::Checkpoint& c);
  PassKeeper(const PassKeeper&) = delete;
  PassKeeper& operator=(const PassKeeper&) = delete;

  /// Where the render begins: after the resumed checkpoint's passes, or at the start.
  glint::RenderStart start() const;

  /// The pass callback: false stops the render after this pass.
  bool pass_done(const glint::PassReport& pass);
  glint::PassCallback callback();

  bool time_is_up() const { return time_is_up_; }
  /// Writes the checkpoint of the last completed pass, whose sums are `sums` (the render's
  /// RenderResult::sums, kept with RenderControl::keep_sums), to --checkpoint's file, piece by
  /// piece. Throws ImageWriteError naming the file.
  void write_final_checkpoint(const glint::PixelSums& sums) const;

 private:
  const Program& program_;
  const Options& options_;
  glint::CheckpointKey key_;
  std::optional<glint::Checkpoint> resumed_;
  int last_passes_ = 0, last_spp_ = 0;  ///< of the last completed pass
  bool time_is_up_ = false;
  double last_checkpoint_ = 0.0;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
