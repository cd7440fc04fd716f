// pass_keeper.hpp's definitions.

#include "pass_keeper.hpp"

#include <cstdio>
#include <string>
#include <utility>

#include "glint/error.hpp"
#include "glint/variants.hpp"
#include "out_of_memory.hpp"
#include "staged_outputs.hpp"
#include "untrusted_text.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

std::optional<glint::Checkpoint> PassKeeper::read_resumed(const Options& options) {
  if (!options.resume) return std::nullopt;
  const std::string& file = *options.resume;
  return with_memory_for([&] { return "reading the checkpoint " + file; },
                         [&] { return glint::read_checkpoint(file); });
}

std::string PassKeeper::made_by(const glint::Checkpoint& c) {
  const std::string legacy =
      std::string(", ") + std::string(execution_model_name(ExecutionModel::wavefront));
  const std::string& name = c.key.variant;
  return name.ends_with(legacy) ? name.substr(0, name.size() - legacy.size()) : name;
}

PassKeeper::PassKeeper(const Program& program, const Options& options,
                       const glint::RenderSettings& settings, std::uint64_t scene_hash,
                       std::optional<glint::Checkpoint> resumed)
    : program_(program), options_(options), resumed_(std::move(resumed)) {
  // Either execution model continues a checkpoint of either: their sums are the same bits.
  if (options.checkpoint || options.resume)
    key_ = glint::CheckpointKey::of(scene_hash, program.variant, settings);
  if (options.resume) {
    const std::string& file = *options.resume;
    if (!resumed_) resumed_ = read_resumed(options);
    resumed_->key.variant = made_by(*resumed_);
    // Named here rather than by check_checkpoint_matches: the name is the file's, which anyone
    // may have written, so it is shown escaped.
    if (resumed_->key.variant != key_.variant) {
      // Where the name is a variant's, the program that continues the render.
      std::string continued_by;
      glint::variants::visit_by_name(resumed_->key.variant, [&]<typename V>() {
        continued_by = " (glint-render-" + dashed_variant_name(V::info.name) + " continues it)";
      });
      throw glint::CheckpointError("cannot resume from " + file + ": it was made by variant '" +
                                   escaped(resumed_->key.variant) + "', this is variant '" +
                                   key_.variant + "'" + continued_by);
    }
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
