#pragma once
// The scene file reader: text in, validated SceneDescription out. The format is specified in
// docs/scene-format.md; in short, one statement per line, `#` starts a comment,
// `key=value` tokens, vectors `x,y,z`:
//
//   image  width=800 height=600 spp=64
//   light  position=-10,20,40 intensity=4000
//   sphere center=0,0,0 radius=10 diffuse=0.5 mirror=0.5
//
// Every problem, syntactic or semantic, is a SceneError "SOURCE:LINE: error: PROBLEM"; the
// reader stops at the first one. Input is untrusted: it is read in one linear pass with no
// recursion, numbers go through std::from_chars (locale-independent, whole token consumed)
// and every quoted piece of input in a message is escaped and shortened.

#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <unordered_map>
#include <utility>
#include <vector>

#include "glint/detail/text.hpp"
#include "glint/instruction_set.hpp"
#include "glint/io/input_file.hpp"
#include "glint/io/texture_reader.hpp"
#include "glint/math/vector.hpp"
#include "glint/scene/material.hpp"
#include "glint/scene/metals.hpp"
#include "glint/scene/scene_description.hpp"
#include "glint/scene/scene_error.hpp"
#include "glint/scene/validate.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Lines longer than this are rejected: no valid statement comes near it, and a binary file
/// fed by mistake usually trips it (or the NUL check) on its first line.
inline constexpr std::size_t kMaxSceneLineLength = 1 << 16;
/// read_scene_file refuses larger files, so that a pipe or device that never ends
/// (/dev/zero, `yes |`) cannot exhaust memory. Ten million spheres take about 700 MB.
inline constexpr std::uintmax_t kMaxSceneFileSize = std::uintmax_t{1} << 30;

/// How far reading a scene has got, for a progress display: `done` of `total` bytes of the file
/// read (total 0 when the size is not known beforehand, as for a pipe), then of its text parsed
/// and checked.
struct SceneReadProgress {
  enum class Stage { reading, parsing } stage = Stage::reading;
  std::uint64_t done = 0;
  std::uint64_t total = 0;
};
/// Called on the reading thread, about every mebibyte read and every 65536 lines parsed.
using SceneReadCallback = std::function<void(const SceneReadProgress&)>;

namespace detail::scene_reader {

/// Input quoted in an error message: control and non-ASCII bytes escaped, long text cut, so
/// that a message stays one readable line whatever the file contains.
inline std::string quoted(std::string_view text) {
  constexpr std::size_t kMaxShown = 40;
  std::string out = "'";
  const std::size_t shown = text.size() > kMaxShown ? kMaxShown : text.size();
  for (std::size_t i = 0; i < shown; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f && c != '\\') {
      out += static_cast<char>(c);
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  if (shown < text.size()) out += "...";
  return out + "'";
}

inline std::string join(std::span<const std::string_view> words) {
  std::string out;
  for (std::string_view word : words) {
    if (!out.empty()) out += ", ";
    out += word;
  }
  return out;
}

inline bool is_space(char c) {
  return c == ' ' || c == '\t';
}

inline bool is_identifier(std::string_view name) {
  if (name.empty() || (name[0] >= '0' && name[0] <= '9')) return false;
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

// Key tables. The material keys come first in the sphere table so that one function reads an
// inline material and a named one with the same indices.
enum MaterialKey : int {
  kDiffuse,
  kColor,
  kMirror,
  kMirrorColor,
  kTransparent,
  kTransparentColor,
  kIor,
  kEmission,
  kMirrorRoughness,
  kMetal,
  kMetalEta,
  kMetalK,
  kTransparentRoughness,
  kMaterialKeyCount
};
enum SphereKey : int {
  kCenter = kMaterialKeyCount,
  kRadius,
  kMaterialName,
  kShading,
  kTexture,
  kTextureAxis,
  kTextureTurn
};
inline constexpr std::string_view kMaterialKeys[] = {"diffuse",
                                                     "color",
                                                     "mirror",
                                                     "mirror_color",
                                                     "transparent",
                                                     "transparent_color",
                                                     "ior",
                                                     "emission",
                                                     "mirror_roughness",
                                                     "metal",
                                                     "metal_eta",
                                                     "metal_k",
                                                     "transparent_roughness"};
/// A sphere's keys: every material key (an inline material), then its own.
inline constexpr std::string_view kSphereOwnKeys[] = {
    "center", "radius", "material", "shading", "texture", "texture_axis", "texture_turn"};
inline constexpr auto kSphereKeys = [] {
  std::array<std::string_view, std::size(kMaterialKeys) + std::size(kSphereOwnKeys)> keys{};
  std::size_t i = 0;
  for (const std::string_view key : kMaterialKeys)
    keys[i++] = key;
  for (const std::string_view key : kSphereOwnKeys)
    keys[i++] = key;
  return keys;
}();

enum ImageKey : int { kWidth, kHeight, kSpp, kMaxDepthKey };
inline constexpr std::string_view kImageKeys[] = {"width", "height", "spp", "max_depth"};
enum CameraKey : int { kPosition, kLookAt, kUp, kFov, kNear, kAperture, kFocus, kProjection };
inline constexpr std::string_view kCameraKeys[] = {"position", "look_at",  "up",    "fov",
                                                   "near",     "aperture", "focus", "projection"};
enum LightKey : int { kLightPosition, kIntensity, kLightColor };
inline constexpr std::string_view kLightKeys[] = {"position", "intensity", "color"};
inline constexpr std::string_view kAntialiasKeys[] = {"sigma"};
enum BackgroundKey : int {
  kBackgroundColor,
  kBackgroundImage,
  kBackgroundAxis,
  kBackgroundTurn,
  kBackgroundScale
};
inline constexpr std::string_view kBackgroundKeys[] = {"color", "image", "axis", "turn", "scale"};
inline constexpr std::string_view kMediumKeys[] = {"ior"};

static_assert(std::size(kMaterialKeys) == kMaterialKeyCount &&
              kTextureTurn + 1 == int(std::size(kSphereKeys)));

inline constexpr std::string_view kStatements[] = {"image",  "camera", "antialias", "background",
                                                   "medium", "light",  "material",  "sphere"};

/// A statement and the keys the reader accepts for it (for `material`, after its name).
struct StatementKeys {
  std::string_view statement;
  std::span<const std::string_view> keys;
};
inline constexpr StatementKeys kStatementKeys[] = {
    {"image", kImageKeys},           {"camera", kCameraKeys}, {"antialias", kAntialiasKeys},
    {"background", kBackgroundKeys}, {"medium", kMediumKeys}, {"light", kLightKeys},
    {"material", kMaterialKeys},     {"sphere", kSphereKeys}};
static_assert(std::size(kStatementKeys) == std::size(kStatements) && [] {
  for (std::size_t i = 0; i < std::size(kStatements); ++i)
    if (kStatementKeys[i].statement != kStatements[i]) return false;
  return true;
}());

/// The key=value tokens of one statement, indexed by their position in the statement's table.
struct Fields {
  static constexpr std::size_t kMaxKeys = 32;
  std::array<std::string_view, kMaxKeys> values{};
  std::uint32_t present = 0;
  bool has(int key) const { return (present >> key) & 1u; }
  std::string_view operator[](int key) const { return values[static_cast<std::size_t>(key)]; }
};
// Every statement's keys fit in Fields (one bit of `present` each).
static_assert([] {
  for (const StatementKeys& statement : kStatementKeys)
    if (statement.keys.size() > Fields::kMaxKeys) return false;
  return true;
}());

struct StringHash {
  using is_transparent = void;
  std::size_t operator()(std::string_view s) const noexcept {
    return std::hash<std::string_view>{}(s);
  }
};

class Parser {
 public:
  explicit Parser(std::string source, SceneReadCallback progress = {})
      : progress_(std::move(progress)) {
    scene_.source = std::move(source);
  }

  SceneDescription parse(std::string_view text) {
    // A UTF-8 byte order mark, as some Windows editors write, is not part of the first line.
    if (text.starts_with("\xEF\xBB\xBF")) text.remove_prefix(3);
    // Sized once: growing a vector of a million spheres by doubling costs more than this scan.
    scene_.spheres.reserve(count_sphere_lines(text));
    std::size_t start = 0;
    while (start < text.size()) {
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      if (line_ == INT_MAX) fail("too many lines");
      ++line_;
      if (progress_ && line_ % kLinesPerReport == 0)
        progress_({SceneReadProgress::Stage::parsing, start, text.size()});
      parse_line(text.substr(start, end - start));
      start = end + 1;
    }
    line_ = 0;
    validate(scene_);
    return std::move(scene_);
  }

 private:
  struct NamedMaterial {
    Material material;
    int line;
  };

  /// An upper bound on the number of spheres: lines starting with "sphere" that are long
  /// enough to hold a valid one. The length test keeps a bogus file from reserving more than
  /// a valid file of its size would need.
  static std::size_t count_sphere_lines(std::string_view text) {
    constexpr std::size_t kShortestSphere = sizeof("sphere center=0,0,0 radius=1") - 1;
    std::size_t count = 0;
    std::size_t start = 0;
    while (start < text.size()) {
      while (start < text.size() && is_space(text[start]))
        ++start;
      std::size_t end = text.find('\n', start);
      if (end == std::string_view::npos) end = text.size();
      if (end - start >= kShortestSphere && text.substr(start, 6) == "sphere") ++count;
      start = end + 1;
    }
    return count;
  }

  [[noreturn]] void fail(const std::string& problem) const {
    throw SceneError(scene_.source, line_, problem);
  }

  void parse_line(std::string_view line) {
    if (line.size() > kMaxSceneLineLength)
      fail(detail::concat(
          {"line is longer than ", std::to_string(kMaxSceneLineLength), " characters"}));
    if (line.find('\0') != std::string_view::npos)
      fail("line contains a NUL byte (is this a text file?)");
    if (line.ends_with('\r')) line.remove_suffix(1);  // CRLF line endings
    if (const std::size_t hash = line.find('#'); hash != std::string_view::npos)
      line = line.substr(0, hash);

    tokens_.clear();
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_space(line[i]))
        ++i;
      const std::size_t begin = i;
      while (i < line.size() && !is_space(line[i]))
        ++i;
      if (i > begin) tokens_.push_back(line.substr(begin, i - begin));
    }
    if (tokens_.empty()) return;

    const std::string_view keyword = tokens_[0];
    const std::span<const std::string_view> rest(tokens_.data() + 1, tokens_.size() - 1);
    if (keyword == "sphere") return read_sphere(rest);  // first: a big scene is mostly spheres
    if (keyword == "light") return read_light(rest);
    if (keyword == "material") return read_named_material(rest);
    if (keyword == "image") return read_image(rest);
    if (keyword == "camera") return read_camera(rest);
    if (keyword == "antialias") return read_antialias(rest);
    if (keyword == "background") return read_background(rest);
    if (keyword == "medium") return read_medium(rest);
    fail(detail::concat(
        {"unknown statement ", quoted(keyword), " (expected one of: ", join(kStatements), ")"}));
  }

  /// Statements that configure the whole scene may appear once; `line` is where the scene
  /// records the statement, still 0 if it has not been seen.
  void once(std::string_view statement, int& line) {
    if (line != 0)
      fail(detail::concat({"duplicate '", statement, "' statement (first given at line ",
                           std::to_string(line), ")"}));
    line = line_;
  }

  Fields fields(std::string_view statement, std::span<const std::string_view> keys,
                std::span<const std::string_view> tokens) const {
    Fields result;
    for (std::string_view token : tokens) {
      const std::size_t equals = token.find('=');
      if (equals == std::string_view::npos)
        fail(detail::concat({"expected key=value, got ", quoted(token),
                             " (no spaces are allowed around '=' or in vectors)"}));
      const std::string_view key = token.substr(0, equals);
      const std::string_view value = token.substr(equals + 1);
      if (key.empty()) fail(detail::concat({"missing key before '=' in ", quoted(token)}));
      std::size_t index = 0;
      while (index < keys.size() && keys[index] != key)
        ++index;
      if (index == keys.size())
        fail(detail::concat(
            {"unknown key ", quoted(key), " for ", statement, " (valid keys: ", join(keys), ")"}));
      if (result.has(static_cast<int>(index)))
        fail(detail::concat({"key '", key, "' given twice"}));
      if (value.empty()) fail(detail::concat({"missing value for '", key, "'"}));
      result.values[index] = value;
      result.present |= 1u << index;
    }
    return result;
  }

  void require(const Fields& f, std::span<const std::string_view> keys, int key,
               std::string_view statement) const {
    if (!f.has(key))
      fail(detail::concat(
          {"missing required key '", keys[static_cast<std::size_t>(key)], "' for ", statement}));
  }

  float number(std::string_view key, std::string_view text) const {
    std::string_view digits = text;
    // from_chars takes no '+' sign; accept one, but not "+-1".
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
    const char* const end = digits.data() + digits.size();
    float value = 0.0f;
    const std::from_chars_result result = std::from_chars(digits.data(), end, value);
    if (result.ec == std::errc::result_out_of_range) {
      // Out of float's range either way; in double we learn which way. Underflow is only
      // rounding (to zero), overflow is an error.
      double wide = 0.0;
      const std::from_chars_result again = std::from_chars(digits.data(), end, wide);
      const bool parsed = again.ec == std::errc{} && again.ptr == end;
      if (parsed && std::abs(wide) < 1.0) {
        value = static_cast<float>(wide);
      } else if (parsed) {
        fail(detail::concat({"'", key, "' must be a finite number, got ", quoted(text),
                             " (too large for a 32-bit float)"}));
      } else {
        fail(detail::concat({"number ", quoted(text), " for '", key, "' is out of range"}));
      }
    } else if (result.ec != std::errc{} || result.ptr != end) {
      fail(detail::concat({"bad number ", quoted(text), " for '", key, "'"}));
    }
    if (!std::isfinite(value))
      fail(detail::concat({"'", key, "' must be a finite number, got ", quoted(text)}));
    return value;
  }

  int integer(std::string_view key, std::string_view text) const {
    std::string_view digits = text;
    if (digits.size() > 1 && digits[0] == '+' && digits[1] != '-') digits.remove_prefix(1);
    int value = 0;
    const char* const end = digits.data() + digits.size();
    const auto [ptr, ec] = std::from_chars(digits.data(), end, value);
    if (ec == std::errc::result_out_of_range)
      fail(detail::concat({"integer ", quoted(text), " for '", key, "' is out of range"}));
    if (ec != std::errc{} || ptr != end)
      fail(detail::concat({"'", key, "' must be an integer, got ", quoted(text)}));
    return value;
  }

  Vec3 vec3(std::string_view key, std::string_view text) const {
    std::string_view parts[3];
    std::size_t count = 0;
    std::size_t start = 0;
    while (true) {
      const std::size_t comma = text.find(',', start);
      const std::size_t stop = comma == std::string_view::npos ? text.size() : comma;
      if (count < 3) parts[count] = text.substr(start, stop - start);
      ++count;
      if (comma == std::string_view::npos) break;
      start = comma + 1;
    }
    if (count != 3)
      fail(detail::concat({"'", key, "' needs 3 components x,y,z, got ", std::to_string(count),
                           " in ", quoted(text)}));
    return Vec3(number(key, parts[0]), number(key, parts[1]), number(key, parts[2]));
  }

  float coefficient(std::string_view key, std::string_view text) const {
    const float value = number(key, text);
    if (!(value >= 0.0f && value <= 1.0f))
      fail(detail::concat({"'", key, "' must be in [0, 1], got ", quoted(text)}));
    return value;
  }

  /// The material keys of `f` (indices as in kMaterialKeys) over the defaults.
  Material material_from(const Fields& f) const {
    Material m;
    if (f.has(kColor)) m.diffuse_color = vec3("color", f[kColor]);
    if (f.has(kMirror)) m.mirror = coefficient("mirror", f[kMirror]);
    if (f.has(kMirrorColor)) m.mirror_color = vec3("mirror_color", f[kMirrorColor]);
    if (f.has(kTransparent)) m.transparent = coefficient("transparent", f[kTransparent]);
    if (f.has(kTransparentColor))
      m.transparent_color = vec3("transparent_color", f[kTransparentColor]);
    if (f.has(kIor)) m.ior = number("ior", f[kIor]);
    if (f.has(kEmission)) m.emission = vec3("emission", f[kEmission]);
    if (f.has(kMirrorRoughness))
      m.mirror_roughness = coefficient("mirror_roughness", f[kMirrorRoughness]);
    if (f.has(kTransparentRoughness))
      m.transparent_roughness = coefficient("transparent_roughness", f[kTransparentRoughness]);
    if (f.has(kMetal)) {
      if (f.has(kMetalEta) || f.has(kMetalK))
        fail("give a metal by name (metal=) or by its index (metal_eta= and metal_k=), not both");
      const std::optional<Metal> metal = metal_named(f[kMetal]);
      if (!metal) {
        std::string expected;
        for (const std::string_view known : kMetalNames)
          expected += std::string(expected.empty() ? "" : ", ") + std::string(known);
        fail(detail::concat({"unknown metal ", quoted(f[kMetal]), " (expected ", expected, ")"}));
      }
      m.metal_eta = metal->eta;
      m.metal_k = metal->k;
    } else if (f.has(kMetalEta) != f.has(kMetalK)) {
      fail("metal_eta and metal_k go together: give both, or name a metal with metal=");
    } else if (f.has(kMetalEta)) {
      m.metal_eta = vec3("metal_eta", f[kMetalEta]);
      m.metal_k = vec3("metal_k", f[kMetalK]);
    }
    // A metal is a mirror lobe: naming one without a mirror coefficient makes the sphere all
    // metal (but for its transparency).
    if (m.is_metal() && !f.has(kMirror)) m.mirror = 1.0f - m.transparent;
    if (f.has(kDiffuse)) {
      m.diffuse = coefficient("diffuse", f[kDiffuse]);
    } else {
      // Whatever the other lobes leave. Float inputs such as 0.1 and 0.9 do not add up to
      // exactly 1, so a remainder within rounding of 0 is taken to mean 0.
      const double rest = 1.0 - double(m.mirror) - double(m.transparent);
      if (rest < -1e-5)
        fail(detail::concat({"mirror + transparent must not exceed 1, got ",
                             detail::format_number(m.mirror + m.transparent)}));
      m.diffuse = rest > 1e-6 ? static_cast<float>(rest) : 0.0f;
    }
    detail::check_material(scene_, m, line_);
    return m;
  }

  void read_image(std::span<const std::string_view> tokens) {
    ImageDescription& image = scene_.image;
    once("image", image.line);
    const Fields f = fields("image", kImageKeys, tokens);
    if (f.has(kWidth)) image.width = integer("width", f[kWidth]);
    if (f.has(kHeight)) image.height = integer("height", f[kHeight]);
    if (f.has(kSpp)) image.samples_per_pixel = integer("spp", f[kSpp]);
    if (f.has(kMaxDepthKey)) image.max_depth = integer("max_depth", f[kMaxDepthKey]);
    detail::check_image(scene_);
  }

  void read_camera(std::span<const std::string_view> tokens) {
    CameraDescription& camera = scene_.camera;
    once("camera", camera.line);
    const Fields f = fields("camera", kCameraKeys, tokens);
    if (f.has(kPosition)) camera.position = vec3("position", f[kPosition]);
    if (f.has(kLookAt)) camera.look_at = vec3("look_at", f[kLookAt]);
    if (f.has(kUp)) camera.up = vec3("up", f[kUp]);
    if (f.has(kFov)) camera.fov_degrees = number("fov", f[kFov]);
    if (f.has(kNear)) camera.near = number("near", f[kNear]);
    if (f.has(kAperture)) camera.aperture = number("aperture", f[kAperture]);
    if (f.has(kProjection)) camera.projection = projection(f[kProjection]);
    if (f.has(kFocus)) {
      camera.focus_distance = number("focus", f[kFocus]);
      if (!(camera.focus_distance > 0.0f))
        fail("camera focus must be positive, got " + detail::format_number(camera.focus_distance));
    }
    detail::check_camera(scene_);
  }

  void read_antialias(std::span<const std::string_view> tokens) {
    once("antialias", scene_.antialias_line);
    const Fields f = fields("antialias", kAntialiasKeys, tokens);
    if (f.has(0)) scene_.antialias_sigma = number("sigma", f[0]);
    detail::check_antialias(scene_);
  }

  void read_background(std::span<const std::string_view> tokens) {
    once("background", scene_.background_line);
    const Fields f = fields("background", kBackgroundKeys, tokens);
    if (f.has(kBackgroundColor)) scene_.background = vec3("color", f[kBackgroundColor]);
    if (f.has(kBackgroundAxis)) scene_.background_placement.axis = vec3("axis", f[kBackgroundAxis]);
    if (f.has(kBackgroundTurn))
      scene_.background_placement.turn_degrees = number("turn", f[kBackgroundTurn]);
    if (f.has(kBackgroundScale)) scene_.background_scale = number("scale", f[kBackgroundScale]);
    // A mistake in the keys is named before the file is read.
    if (f.has(kBackgroundImage) && f.has(kBackgroundColor))
      fail("a background is a color or an image, not both: give color= or image=");
    if (!f.has(kBackgroundImage) &&
        (f.has(kBackgroundAxis) || f.has(kBackgroundTurn) || f.has(kBackgroundScale)))
      fail("background axis, turn and scale place an image: give it with image=FILE");
    if (f.has(kBackgroundImage))
      scene_.background_image = image_file("background image", f[kBackgroundImage]);
    detail::check_background(scene_);
  }

  void read_medium(std::span<const std::string_view> tokens) {
    once("medium", scene_.medium_line);
    const Fields f = fields("medium", kMediumKeys, tokens);
    if (f.has(0)) scene_.medium_ior = number("ior", f[0]);
    detail::check_medium(scene_);
  }

  void read_light(std::span<const std::string_view> tokens) {
    const Fields f = fields("light", kLightKeys, tokens);
    require(f, kLightKeys, kLightPosition, "light");
    require(f, kLightKeys, kIntensity, "light");
    PointLight light;
    light.line = line_;
    light.position = vec3("position", f[kLightPosition]);
    light.intensity = number("intensity", f[kIntensity]);
    if (f.has(kLightColor)) light.color = vec3("color", f[kLightColor]);
    detail::check_light(scene_, light);
    scene_.lights.push_back(light);
  }

  void read_named_material(std::span<const std::string_view> tokens) {
    if (tokens.empty() || tokens[0].find('=') != std::string_view::npos)
      fail("material needs a name before its keys (material NAME key=value ...)");
    const std::string_view name = tokens[0];
    if (!is_identifier(name))
      fail(detail::concat({"invalid material name ", quoted(name),
                           " (use letters, digits, '_' and '-', not starting with a digit)"}));
    const Fields f = fields("material", kMaterialKeys, tokens.subspan(1));
    if (const auto it = materials_.find(name); it != materials_.end())
      fail(detail::concat({"duplicate material '", name, "' (first defined at line ",
                           std::to_string(it->second.line), ")"}));
    const Material m = material_from(f);
    materials_.emplace(std::string(name), NamedMaterial{m, line_});
  }

  void read_sphere(std::span<const std::string_view> tokens) {
    const Fields f = fields("sphere", kSphereKeys, tokens);
    require(f, kSphereKeys, kCenter, "sphere");
    require(f, kSphereKeys, kRadius, "sphere");
    SphereDescription sphere;
    sphere.line = line_;
    sphere.center = vec3("center", f[kCenter]);
    sphere.radius = number("radius", f[kRadius]);
    if (!(sphere.radius > 0.0f))
      fail(detail::concat({"sphere radius must be positive, got ", quoted(f[kRadius])}));
    if (f.has(kMaterialName)) {
      constexpr std::uint32_t kInlineKeys = (1u << kMaterialKeyCount) - 1u;
      if (f.present & kInlineKeys) {
        int first = 0;
        while (!f.has(first))
          ++first;
        fail(detail::concat({"sphere has both material=", f[kMaterialName], " and inline key '",
                             kMaterialKeys[first], "'; use one or the other"}));
      }
      const auto it = materials_.find(f[kMaterialName]);
      if (it == materials_.end())
        fail(detail::concat({"undefined material ", quoted(f[kMaterialName]),
                             " (materials must be defined before the spheres that use them)"}));
      sphere.material = it->second.material;
    } else {
      sphere.material = material_from(f);
    }
    if (f.has(kShading)) sphere.shading = shading(f[kShading]);
    if (f.has(kTexture)) {
      if (!f.has(kShading)) sphere.shading = ShadingKind::texture;
      // A mistake in the keys is named before the file is read.
      if (const std::string problem = detail::texture_shading_problem(sphere.shading, true);
          !problem.empty())
        fail(problem);
      sphere.texture = image_file("texture", f[kTexture]);
    } else if (f.has(kTextureAxis) || f.has(kTextureTurn)) {
      fail("texture_axis and texture_turn place an image: give it with texture=FILE");
    }
    if (f.has(kTextureAxis)) sphere.texture_placement.axis = vec3("texture_axis", f[kTextureAxis]);
    if (f.has(kTextureTurn))
      sphere.texture_placement.turn_degrees = number("texture_turn", f[kTextureTurn]);
    detail::check_sphere(scene_, sphere);
    scene_.spheres.push_back(sphere);
  }

  Projection projection(std::string_view text) const {
    for (int i = 0; i < kProjectionCount; ++i)
      if (text == to_string(Projection(i))) return Projection(i);
    fail(detail::concat({"unknown projection ", quoted(text), " (expected ",
                         to_string(Projection::perspective), " or ",
                         to_string(Projection::equirectangular), ")"}));
  }

  ShadingKind shading(std::string_view text) const {
    std::string expected;
    for (int i = 0; i < kShadingKindCount; ++i) {
      const auto kind = static_cast<ShadingKind>(i);
      if (text == to_string(kind)) return kind;
      expected += (i == 0 ? "" : i + 1 == kShadingKindCount ? " or " : ", ");
      expected += to_string(kind);
    }
    fail(detail::concat({"unknown shading ", quoted(text), " (expected ", expected, ")"}));
  }

  /// The image of `texture=FILE` or `image=FILE` (`what` names it in an error), read once
  /// however many statements show it. A relative path is taken from the directory of the scene
  /// file (of `source`).
  std::shared_ptr<const Texture> image_file(std::string_view what, std::string_view file) {
    const std::filesystem::path given{std::string(file)};
    const std::filesystem::path path =
        given.is_absolute() ? given : std::filesystem::path(scene_.source).parent_path() / given;
    const std::string key = path.lexically_normal().string();
    if (const auto it = textures_.find(key); it != textures_.end()) return it->second;
    try {
      auto image = std::make_shared<const Texture>(read_texture(path, std::string(file)));
      textures_.emplace(key, image);
      return image;
    } catch (const ImageReadError& error) {
      fail(detail::concat({what, " ", quoted(file), ": ", error.what()}));
    }
  }

  static constexpr int kLinesPerReport = 1 << 16;

  SceneReadCallback progress_;
  SceneDescription scene_;
  int line_ = 0;
  std::vector<std::string_view> tokens_;  // reused across lines: no allocation per line
  std::unordered_map<std::string, NamedMaterial, StringHash, std::equal_to<>> materials_;
  std::unordered_map<std::string, std::shared_ptr<const Texture>> textures_;
};

}  // namespace detail::scene_reader

/// Every statement of the scene format with the keys the reader accepts for it, from the
/// reader's own tables: what docs/scene-format.md must document (`ctest -L docs` checks it).
inline constexpr std::span<const detail::scene_reader::StatementKeys> scene_format_statements() {
  return detail::scene_reader::kStatementKeys;
}

/// Parses and validates a scene; `source` names it in error messages ("FILE:LINE: error: ...").
inline SceneDescription read_scene_text(std::string_view text, std::string source = "<scene>",
                                        const SceneReadCallback& progress = {}) {
  return detail::scene_reader::Parser(std::move(source), progress).parse(text);
}

/// The text of a scene file, for read_scene_text (read_scene_file is both): a program that
/// reads the file once and parses it in several processes (glint-render-mpi). Refuses what
/// read_scene_file refuses before parsing, with the same SceneError: a file that cannot be
/// opened or read (line 0), one beyond kMaxSceneFileSize, a NUL byte (its line). `progress`, if
/// set, follows the reading.
inline std::string read_scene_file_text(const std::filesystem::path& path,
                                        const SceneReadCallback& progress = {}) {
  const std::string source = path.string();
  // Through InputFile, the one reader of untrusted files: it refuses a directory, knows the size
  // of a regular file before anything is read, and reads a pipe or a device as it comes.
  bool opened = false;
  const auto fail = [&](const std::string& problem) {
    constexpr std::string_view kReadError = "read error: ";
    if (!opened) throw SceneError(source, 0, detail::concat({"cannot open file: ", problem}));
    const std::string_view why = std::string_view(problem).starts_with(kReadError)
                                     ? std::string_view(problem).substr(kReadError.size())
                                     : std::string_view(problem);
    throw SceneError(source, 0, detail::concat({"cannot read file: ", why}));
  };
  InputFile file(path, fail);
  opened = true;
  std::string text;
  const std::uint64_t expected_size = file.size().value_or(0);  // 0: a pipe or a device
  const auto too_large = [&] {
    throw SceneError(
        source, 0,
        detail::concat({"file is larger than ", std::to_string(kMaxSceneFileSize >> 20), " MiB"}));
  };
  // Reserved from the size of a regular file, so that a big scene is copied only once; one
  // beyond the limit is refused before it is read.
  if (file.size()) {
    if (*file.size() > kMaxSceneFileSize) too_large();
    text.reserve(static_cast<std::size_t>(*file.size()));
  }
  // Text without line ends (binary data free of NUL bytes, an endless stream of one
  // character) is refused once a line exceeds what the parser accepts, as the parser would.
  std::size_t line_length = 0;
  std::int64_t lines = 0;
  char buffer[1 << 16];
  for (std::size_t reads = 1;; ++reads) {
    if (progress && reads % 16 == 0)
      progress({SceneReadProgress::Stage::reading, text.size(), expected_size});
    const std::size_t got = file.read(buffer, sizeof buffer);
    // Binary input (an image, /dev/zero) is refused at its first NUL byte, with the line the
    // parser would name, rather than after reading up to the size limit.
    if (const void* nul = std::memchr(buffer, '\0', got)) {
      const auto in_buffer = static_cast<std::size_t>(static_cast<const char*>(nul) - buffer);
      const std::int64_t lines_before = lines + std::count(buffer, buffer + in_buffer, '\n');
      throw SceneError(source, static_cast<int>(std::min<std::int64_t>(lines_before + 1, INT_MAX)),
                       "line contains a NUL byte (is this a text file?)");
    }
    for (const char *at = buffer, *end = buffer + got; at < end;) {
      const auto* line_end = static_cast<const char*>(std::memchr(at, '\n', std::size_t(end - at)));
      line_length += std::size_t((line_end ? line_end : end) - at);
      if (line_length > kMaxSceneLineLength)
        throw SceneError(source, static_cast<int>(std::min<std::int64_t>(lines + 1, INT_MAX)),
                         detail::concat({"line is longer than ",
                                         std::to_string(kMaxSceneLineLength), " characters"}));
      if (!line_end) break;
      line_length = 0;
      ++lines;
      at = line_end + 1;
    }
    if (got > 0) {
      if (text.size() + got > kMaxSceneFileSize) too_large();
      text.append(buffer, got);
    }
    if (got < sizeof buffer) break;  // the end: InputFile's reads fail through `fail`
  }
  return text;
}

/// Reads a scene file; errors name the path as given. A file that cannot be opened or read
/// is a SceneError with line 0. `progress`, if set, follows the reading and the parsing.
inline SceneDescription read_scene_file(const std::filesystem::path& path,
                                        const SceneReadCallback& progress = {}) {
  return read_scene_text(read_scene_file_text(path, progress), path.string(), progress);
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
