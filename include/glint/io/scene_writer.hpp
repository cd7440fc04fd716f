#pragma once
// Writes a SceneDescription in the glint scene format (docs/scene-format.md), the inverse of
// io/scene_reader.hpp: reading the text back gives the same description, every float bit for
// bit (line numbers and the source label aside, which belong to the file, not the scene).
//
// Floats are printed as the shortest decimal text that parses back to the same float
// (detail::write_number, in detail/text.hpp); iostreams with a fixed precision either lose bits
// or print noise digits. Every sphere gets an inline material: the description keeps no material
// names, and inline keys make each line self-contained, so a generated file can be cut and pasted
// freely.

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <ostream>
#include <string>
#include <string_view>
#include <system_error>

#include "glint/detail/text.hpp"
#include "glint/error.hpp"
#include "glint/instruction_set.hpp"
#include "glint/scene/scene_description.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// A description that the format cannot express (a number that is not finite, a texture name
/// that is no token of the format).
class SceneWriteError : public Error {
 public:
  using Error::Error;
};

namespace detail {

inline bool same_bits(float a, float b) {
  return std::bit_cast<std::uint32_t>(a) == std::bit_cast<std::uint32_t>(b);
}
inline bool same_bits(const Vec3& a, const Vec3& b) {
  return same_bits(a.x, b.x) && same_bits(a.y, b.y) && same_bits(a.z, b.z);
}

/// Appends the shortest decimal form of v that reads back to the same float, in plain notation
/// unless that is much longer (detail/text.hpp), so that a wall prints as 100000 rather than
/// 1e+05 and a file stays easy to read and edit by hand.
inline void append_float(std::string& out, float v, const char* what) {
  if (!std::isfinite(v))
    throw SceneWriteError(std::string("cannot write a scene with a non-finite ") + what);
  append_number(out, v, FloatNotation::plain_unless_long);
}

inline void append_int(std::string& out, long long v) {
  char buffer[24];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  out.append(buffer, r.ptr);
}

inline void append_vec(std::string& out, const Vec3& v, const char* what) {
  append_float(out, v.x, what);
  out += ',';
  append_float(out, v.y, what);
  out += ',';
  append_float(out, v.z, what);
}

inline void append_key(std::string& out, const char* key, float v) {
  out += ' ';
  out += key;
  out += '=';
  append_float(out, v, key);
}

inline void append_key(std::string& out, const char* key, const Vec3& v) {
  out += ' ';
  out += key;
  out += '=';
  append_vec(out, v, key);
}

/// The reader fills an omitted diffuse coefficient with 1 - mirror - transparent, snapping a
/// remainder within rounding of 0 to 0. Omitting it is safe only when that formula gives
/// exactly the stored bits however it is evaluated (left to right, grouped, or in double) and
/// the value is clear of the snapping, which holds for the common pure materials.
inline bool diffuse_is_implied(const Material& m) {
  const float left_to_right = 1.0f - m.mirror - m.transparent;
  const float grouped = 1.0f - (m.mirror + m.transparent);
  const auto in_double = static_cast<float>(1.0 - double(m.mirror) - double(m.transparent));
  const bool clear_of_zero = same_bits(m.diffuse, 0.0f) || m.diffuse >= 1e-4f;
  return clear_of_zero && same_bits(m.diffuse, left_to_right) && same_bits(m.diffuse, grouped) &&
         same_bits(m.diffuse, in_double);
}

/// Only keys that differ from the format's defaults are written, compared bit for bit so that
/// even -0 survives the round trip.
inline void append_material(std::string& out, const Material& m) {
  const Material defaults{};
  if (!diffuse_is_implied(m)) append_key(out, "diffuse", m.diffuse);
  if (!same_bits(m.diffuse_color, defaults.diffuse_color))
    append_key(out, "color", m.diffuse_color);
  if (!same_bits(m.mirror, defaults.mirror)) append_key(out, "mirror", m.mirror);
  if (!same_bits(m.mirror_color, defaults.mirror_color))
    append_key(out, "mirror_color", m.mirror_color);
  if (!same_bits(m.transparent, defaults.transparent))
    append_key(out, "transparent", m.transparent);
  if (!same_bits(m.transparent_color, defaults.transparent_color))
    append_key(out, "transparent_color", m.transparent_color);
  if (!same_bits(m.ior, defaults.ior)) append_key(out, "ior", m.ior);
  if (!same_bits(m.emission, defaults.emission)) append_key(out, "emission", m.emission);
  if (!same_bits(m.mirror_roughness, defaults.mirror_roughness))
    append_key(out, "mirror_roughness", m.mirror_roughness);
  if (!same_bits(m.transparent_roughness, defaults.transparent_roughness))
    append_key(out, "transparent_roughness", m.transparent_roughness);
  // By its index, not its name: the reader's mirror default for a named metal is then never
  // relied on, and a metal of one's own round-trips as well.
  if (m.is_metal()) {
    append_key(out, "metal_eta", m.metal_eta);
    append_key(out, "metal_k", m.metal_k);
  }
}

/// An image by the name it was read with (the path as its scene file gave it, relative to that
/// file's directory) as `key`=NAME, and its placement where not the default as
/// `axis_key`= and `turn_key`=.
inline void append_image(std::string& out, const Texture& image, const TexturePlacement& placement,
                         const char* key, const char* axis_key, const char* turn_key) {
  const std::string& name = image.name();
  const bool writable = !name.empty() && std::none_of(name.begin(), name.end(), [](char c) {
    return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '#' || c == '\0';
  });
  if (!writable)
    throw SceneWriteError(
        "an image's name must be a path without spaces, tabs, line ends or '#'"
        " to be written in a scene file, got '" +
        name + "'");
  out += ' ';
  out += key;
  out += '=';
  out += name;
  const TexturePlacement defaults{};
  if (!same_bits(placement.axis, defaults.axis)) append_key(out, axis_key, placement.axis);
  if (!same_bits(placement.turn_degrees, defaults.turn_degrees))
    append_key(out, turn_key, placement.turn_degrees);
}

/// Formats the scene line by line into `buffer`, handing it to `sink` whenever it passes
/// `chunk` bytes and once at the end, so that a million-sphere scene can stream to a file
/// without first being held whole in memory.
template <typename Sink>
void emit_scene(const SceneDescription& scene, std::string& buffer, std::size_t chunk,
                Sink&& sink) {
  const ImageDescription& image = scene.image;
  buffer += "image width=";
  append_int(buffer, image.width);
  buffer += " height=";
  append_int(buffer, image.height);
  buffer += " spp=";
  append_int(buffer, image.samples_per_pixel);
  buffer += " max_depth=";
  append_int(buffer, image.max_depth);

  const CameraDescription& camera = scene.camera;
  buffer += "\ncamera";
  append_key(buffer, "position", camera.position);
  append_key(buffer, "look_at", camera.look_at);
  append_key(buffer, "up", camera.up);
  append_key(buffer, "fov", camera.fov_degrees);
  append_key(buffer, "near", camera.near);
  if (camera.aperture > 0.0f) append_key(buffer, "aperture", camera.aperture);
  if (camera.focus_distance > 0.0f) append_key(buffer, "focus", camera.focus_distance);
  if (camera.projection != Projection::perspective) {
    buffer += " projection=";
    buffer += to_string(camera.projection);
  }

  buffer += "\nantialias";
  append_key(buffer, "sigma", scene.antialias_sigma);
  buffer += "\nbackground";
  if (scene.background_image) {
    append_image(buffer, *scene.background_image, scene.background_placement, "image", "axis",
                 "turn");
    if (!same_bits(scene.background_scale, 1.0f))
      append_key(buffer, "scale", scene.background_scale);
  } else {
    append_key(buffer, "color", scene.background);
  }
  buffer += "\nmedium";
  append_key(buffer, "ior", scene.medium_ior);
  buffer += '\n';

  for (const PointLight& light : scene.lights) {
    buffer += "light";
    append_key(buffer, "position", light.position);
    append_key(buffer, "intensity", light.intensity);
    append_key(buffer, "color", light.color);
    buffer += '\n';
  }
  for (const SphereDescription& sphere : scene.spheres) {
    buffer += "sphere";
    append_key(buffer, "center", sphere.center);
    append_key(buffer, "radius", sphere.radius);
    append_material(buffer, sphere.material);
    if (sphere.shading != ShadingKind::uniform && sphere.shading != ShadingKind::texture) {
      buffer += " shading=";
      buffer += to_string(sphere.shading);
    }
    if (sphere.texture)
      append_image(buffer, *sphere.texture, sphere.texture_placement, "texture", "texture_axis",
                   "texture_turn");
    buffer += '\n';
    if (buffer.size() >= chunk) sink(buffer);
  }
  sink(buffer);
}

}  // namespace detail

/// Hands the text write_scene would write to `sink`, a std::string_view at a time of about
/// 64 KiB, so that a scene of millions of spheres reaches a file without first being held whole
/// in memory. Throws SceneWriteError as write_scene does (after `sink` had part of the text).
template <typename Sink>
requires std::invocable<Sink&, std::string_view>
void write_scene_in_pieces(const SceneDescription& scene, Sink&& sink) {
  std::string buffer;
  constexpr std::size_t kChunk = std::size_t{1} << 16;
  buffer.reserve(kChunk + 512);
  detail::emit_scene(scene, buffer, kChunk, [&](std::string& text) {
    sink(std::string_view(text));
    text.clear();
  });
}

/// Writes `scene` to `out` in the glint text format. Throws SceneWriteError if a number
/// is not finite (the format has no spelling for it); check `out` for I/O errors afterwards.
inline void write_scene(std::ostream& out, const SceneDescription& scene) {
  write_scene_in_pieces(scene, [&](std::string_view text) {
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
  });
}

/// The text write_scene would write.
inline std::string format_scene(const SceneDescription& scene) {
  std::string text;
  text.reserve(256 + 96 * scene.spheres.size());
  detail::emit_scene(scene, text, static_cast<std::size_t>(-1), [](std::string&) {});
  return text;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
