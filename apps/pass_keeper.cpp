// pass_keeper.hpp's definitions.

#include "pass_keeper.hpp"

#include <cstdio>
#include <string>

#include "glint/error.hpp"
#include "staged_outputs.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

namespace {

/// The variant a checkpoint's key names: for the scalar renderer the variant's name alone, as
/// before there was a wavefront renderer, so that those checkpoints still resume (with --scalar,
/// bit for bit); for the wavefront renderer "NAME, wavefront", so that no checkpoint continues
/// in the other execution model, whose image differs in its last bits.
std::string checkpoint_variant(const Program& program, ExecutionModel model) {
  return model == ExecutionModel::scalar ? std::string(program.variant)
                                         : renderer_name(program, model);
}

/// Refuses a checkpoint of this variant's other execution model, saying so and how to resume
/// it (check_checkpoint_matches would only show two variant names).
void check_execution_model(const glint::Checkpoint& checkpoint, const Program& program,
                           ExecutionModel model, const std::string& file) {
  const ExecutionModel other =
      model == ExecutionModel::scalar ? ExecutionModel::wavefront : ExecutionModel::scalar;
  if (checkpoint.key.variant != checkpoint_variant(program, other)) return;
  throw glint::CheckpointError(
      "cannot resume from " + file + ": it was made by the " +
      std::string(execution_model_name(other)) + " renderer, this render is " +
      std::string(execution_model_name(model)) +
      " (their images differ in the last bits): resume it " +
      (other == ExecutionModel::scalar ? "with" : "without") + " --scalar");
}

}  // namespace

PassKeeper::PassKeeper(const Program& program, const Options& options,
                       const glint::RenderSettings& settings, std::uint64_t scene_hash)
    : program_(program), options_(options) {
  const ExecutionModel model = execution_model(program, options);
  if (options.checkpoint || options.resume)
    key_ = glint::CheckpointKey::of(scene_hash, checkpoint_variant(program, model), settings);
  if (options.resume) {
    resumed_ = glint::read_checkpoint(*options.resume);
    check_execution_model(*resumed_, program, model, *options.resume);
    glint::check_checkpoint_matches(*resumed_, key_, *options.resume);
    last_passes_ = resumed_->passes_done;
    last_spp_ = resumed_->samples_per_pixel_done;
  }
}

glint::RenderStart PassKeeper::start() const {
  return resumed_ ? glint::RenderStart{&resumed_->sums, resumed_->passes_done}
                  : glint::RenderStart{};
}

bool PassKeeper::pass_done(const glint::PassReport& pass) {
  last_passes_ = pass.passes_done;
  last_spp_ = pass.samples_per_pixel;
  const bool last = pass.passes_done == pass.pass_count;
  if (options_.time_limit && pass.elapsed_seconds >= *options_.time_limit && !last) {
    time_is_up_ = true;
    return false;
  }
  // The last pass's checkpoint is written with the images.
  if (options_.checkpoint && !last &&
      pass.elapsed_seconds - last_checkpoint_ >= options_.checkpoint_interval) {
    try {
      write_staged({checkpoint_output(*options_.checkpoint, key_, pass.passes_done,
                                      pass.samples_per_pixel, pass.sums)});
    } catch (const glint::ImageWriteError& error) {
      // Hours of rendering are worth more than one checkpoint: the next one may succeed.
      std::fprintf(stderr, "\n%s: warning: no checkpoint: %s\n", program_.name, error.what());
    }
    last_checkpoint_ = pass.elapsed_seconds;
  }
  return true;
}

glint::PassCallback PassKeeper::callback() {
  return [this](const glint::PassReport& pass) { return pass_done(pass); };
}

void PassKeeper::write_final_checkpoint(const glint::PixelSums& sums) const {
  write_staged({checkpoint_output(*options_.checkpoint, key_, last_passes_, last_spp_, sums)});
}
}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
