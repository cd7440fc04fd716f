#pragma once
// The scene of a run: its file read, parsed and built, with its loading reported
// (load_progress.hpp), the hash a checkpoint records, and the render settings: the scene's, with
// the options' overrides.

#include <cstdint>
#include <string>
#include <string_view>

#include "glint/instruction_set.hpp"
#include "glint/render/render_settings.hpp"
#include "glint/scene/scene.hpp"
#include "program.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE::cli {

class LoadProgress;

/// The text of the scene file `file`, with its reading reported (throws SceneError).
std::string scene_file_text(LoadProgress& loading, const std::string& file);

/// The hash of a scene file's bytes that a checkpoint records: of the text that was parsed, so
/// that any edit, even one that renders the same, makes a checkpoint another scene's.
std::uint64_t scene_text_hash(std::string_view text);

/// `hash` continued over the images the scene's spheres and background show, each once: the
/// part of a scene that is not in its text. A texture file edited between a checkpoint and its
/// resume makes the checkpoint another scene's, as an edit of the scene file does.
std::uint64_t scene_textures_hash(std::uint64_t hash, const glint::Scene& scene);

/// Parses the scene's text, read from `source`, and builds it, with its loading reported. The
/// text is freed once parsed, before the build: it is as large as the scene file (76 MB for a
/// million spheres), and the build is when loading needs the most memory.
glint::Scene parse_and_build(LoadProgress& loading, std::string text, const std::string& source);

/// A scene file read, parsed and built, and the hash a checkpoint records of it.
struct LoadedScene {
  glint::Scene scene;
  /// scene_text_hash of its text continued by scene_textures_hash; 0 unless asked for.
  std::uint64_t text_hash = 0;
};

/// Loads the scene file `file`, reporting its loading on stderr if `report` (load_progress.hpp),
/// hashing its text and its images if `hash` (for checkpoints).
LoadedScene load_scene(const std::string& file, bool report, bool hash);

/// The scene's settings with the options' overrides; throws UsageError when they do not fit
/// together (the scene's own settings were checked when it was read: what fails is an option).
glint::RenderSettings render_settings(const Options& options, const glint::Scene& scene);

}  // namespace glint::inline GLINT_ISA_NAMESPACE::cli
