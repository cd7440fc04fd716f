#pragma once
// Shared by the shipped-scene tests: finding scenes/*.scene and the variant each names,
// rendering one small and fast, and comparing the image with the independent SceneModel
// (scene_model.hpp) in two ways:
//  - `expected_image` + `check_agreement`: for renders short enough that every path ends on
//    direct light (max_depth bounces of mirrors and glass), the exact expectation of each
//    pixel under the variant's pixel filter, estimated by the model from 256 filter offsets
//    per pixel; checked per pixel where the pixel's footprint is smooth, and per channel over
//    all pixels as one z-score.
//  - `hue_groups` + `check_hues`: pixels grouped by the diffuse surface they show through
//    mirrors and glass; each group's mean colour must have that surface's hue.
// Each property test is tagged with the scene file's name ("[fig1a-diffuse]"): the coverage
// test in shipped_scenes_test.cpp fails for a shipped scene without one.

#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "glint/io/scene_reader.hpp"
#include "glint/render/renderer.hpp"
#include "glint/scene/scene.hpp"
#include "glint/variants.hpp"
#include "renderer_types.hpp"
#include "scene_model.hpp"

namespace glint::test {

inline std::vector<std::filesystem::path> shipped_scene_files() {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(GLINT_SOURCE_DIR "/scenes"))
    if (entry.is_regular_file() && entry.path().extension() == ".scene")
      files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  return files;
}

/// The variant named by the file's first "# variant: NAME" line, as scenes/render-all reads
/// it (whitespace removed); "report" when there is none.
inline std::string variant_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    std::size_t i = 0;
    if (line.empty() || line[0] != '#') continue;
    for (i = 1; i < line.size() && std::isspace(static_cast<unsigned char>(line[i])); ++i) {
    }
    if (line.compare(i, 8, "variant:") != 0) continue;
    std::string name;
    for (const char c : line.substr(i + 8))
      if (!std::isspace(static_cast<unsigned char>(c))) name += c;
    return name;
  }
  return "report";
}

/// A shipped scene: its description (as the file gives it) and the variant it names.
struct ShippedScene {
  std::string name;
  std::string variant;
  SceneDescription description;
};

inline ShippedScene load_shipped_scene(const std::string& name) {
  const std::filesystem::path file =
      std::filesystem::path(GLINT_SOURCE_DIR) / "scenes" / (name + ".scene");
  INFO(file.string());
  REQUIRE(std::filesystem::is_regular_file(file));
  return {name, variant_of(file), read_scene_file(file)};
}

/// The scene's settings (pixel filter width included) at a small size.
inline RenderSettings small_settings(const SceneDescription& d, int size, int spp, int max_depth,
                                     std::uint64_t seed = 1) {
  RenderSettings s = RenderSettings::from(Scene::build(d));
  s.width = size;
  s.height = size;
  s.samples_per_pixel = spp;
  s.max_depth = max_depth;
  s.seed = seed;
  s.threads = 2;
  return s;
}

/// Renders with the variant called `variant`, one of those variant_model knows (defined once,
/// in shipped_scenes.cpp, for the four files that use it).
Film render_with(const std::string& variant, const SceneDescription& description,
                 const RenderSettings& settings);

/// What the model must know of a named variant to predict its image: its pixel filter and
/// whether glass has Fresnel reflection. Spelled out here for the variants the shipped scenes
/// use, from their descriptions in variants.hpp.
struct VariantModel {
  bool gaussian_filter = true;  ///< false: every camera ray through the pixel centre
  ModelOptions options;
};

inline VariantModel variant_model(const std::string& variant) {
  VariantModel model;
  if (variant == "report") return model;
  if (variant == "no_fresnel") {
    model.options.fresnel = false;
    return model;
  }
  if (variant == "no_antialiasing") {
    model.gaussian_filter = false;
    return model;
  }
  FAIL("the shipped-scene tests have no model of variant '" << variant << "'");
  return model;
}

/// What the model predicts for one pixel.
struct PixelExpectation {
  bool known = false;          ///< every path of the footprint ends on direct light
  bool smooth = false;         ///< the whole footprint meets the same surfaces, lights and octants
  Vec3d mean{0.0};             ///< expected pixel value
  Vec3d sample_variance{0.0};  ///< variance of one sample
  Vec3d model_variance{0.0};   ///< variance of `mean` itself (the model's own sampling)
};

/// Film points around a pixel centre that the footprint may reach, for the smoothness test:
/// a Gaussian filter's offsets never exceed 5.8 sigma (its sampler draws the radius as
/// sqrt(-2 ln(1 - u)) with u < 1 in single precision), so a ring at 6 sigma bounds it.
/// `sigmas` < 6 gives a smaller neighbourhood that most of the footprint (all but
/// exp(-sigmas^2 / 2) of it) lies in.
inline std::vector<Vec2> footprint_ring(const VariantModel& model, float sigma,
                                        float sigmas = 6.0f) {
  std::vector<Vec2> ring;
  const int points = model.gaussian_filter ? 24 : 8;
  const float radius = model.gaussian_filter ? sigmas * sigma : 0.02f;  // 0.02: rounding only
  for (const float r : {0.5f * radius, radius})
    for (int k = 0; k < points; ++k) {
      const float angle = 2.0f * kPi * float(k) / float(points);
      ring.emplace_back(r * std::cos(angle), r * std::sin(angle));
    }
  return ring;
}

/// The model's expectation for every pixel (row-major) of a render with `settings`, averaged
/// over 256 Gaussian filter offsets per pixel (fixed seed), or the centre ray alone.
inline std::vector<PixelExpectation> expected_image(
    const SceneModel& model, const RenderSettings& settings, const VariantModel& variant,
    const std::function<bool(int, int)>& select = nullptr) {
  constexpr int kOffsets = 256;
  const Pinhole camera(model.description().camera, settings.width, settings.height);
  const std::vector<Vec2> ring = footprint_ring(variant, settings.antialias_sigma);
  std::vector<PixelExpectation> image(std::size_t(settings.width) * std::size_t(settings.height));
  std::mt19937_64 random(12345);
  std::normal_distribution<double> normal(0.0, double(settings.antialias_sigma));
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      PixelExpectation& e = image[std::size_t(y) * std::size_t(settings.width) + std::size_t(x)];
      if (select && !select(x, y)) continue;
      std::uint64_t first_key = 0;
      bool first = true;
      e.known = e.smooth = true;
      const auto trace = [&](double dx, double dy) -> std::optional<Moments> {
        std::uint64_t key = 0;
        const std::optional<Moments> m =
            model.radiance(camera.eye(), camera.direction(x + 0.5 + dx, y + 0.5 + dy), 0,
                           settings.max_depth, variant.options, key);
        if (first) first_key = key;
        e.smooth = e.smooth && key == first_key;
        first = false;
        return m;
      };
      const int offsets = variant.gaussian_filter ? kOffsets : 1;
      Vec3d mean_sum(0.0), mean_square_sum(0.0), second_sum(0.0);
      for (int i = 0; i < offsets && e.known; ++i) {
        const double dx = variant.gaussian_filter ? normal(random) : 0.0;
        const double dy = variant.gaussian_filter ? normal(random) : 0.0;
        const std::optional<Moments> m = trace(dx, dy);
        if (!m) {
          e.known = false;
          break;
        }
        mean_sum += m->mean;
        mean_square_sum += m->mean * m->mean;
        second_sum += m->second;
      }
      if (!e.known) {
        e.smooth = false;
        continue;
      }
      for (const Vec2& p : ring)
        if (!trace(p.x, p.y)) e.smooth = false;
      const double n = offsets;
      e.mean = mean_sum / n;
      e.sample_variance = glm::max(second_sum / n - e.mean * e.mean, Vec3d(0.0));
      e.model_variance = glm::max(mean_square_sum / n - e.mean * e.mean, Vec3d(0.0)) / n;
    }
  return image;
}

/// How a render compares with the model over the selected known pixels.
struct Agreement {
  int known = 0;            ///< selected pixels the model predicts
  int smooth = 0;           ///< of which smooth (checked one by one)
  int smooth_mismatch = 0;  ///< smooth pixels outside the tolerance
  Vec3d z{0.0};             ///< per channel: sum of (pixel - expected) over its standard error
  std::string examples;     ///< the first mismatches
};

/// A smooth pixel must be within 6 standard errors (the render's and the model's) plus a
/// float rounding margin; all known pixels together must be within 5 standard errors per
/// channel.
inline Agreement compare_with_model(const Film& film, const std::vector<PixelExpectation>& model,
                                    int spp,
                                    const std::function<bool(int, int)>& select = nullptr) {
  Agreement a;
  Vec3d difference(0.0), variance(0.0);
  std::ostringstream examples;
  for (int y = 0; y < film.height(); ++y)
    for (int x = 0; x < film.width(); ++x) {
      const PixelExpectation& e =
          model[std::size_t(y) * std::size_t(film.width()) + std::size_t(x)];
      if (!e.known || (select && !select(x, y))) continue;
      ++a.known;
      const Vec3d pixel = to_double(film.at(x, y));
      const Vec3d v = e.sample_variance / double(spp) + e.model_variance;
      difference += pixel - e.mean;
      variance += v;
      if (!e.smooth) continue;
      ++a.smooth;
      bool ok = true;
      for (int k = 0; k < 3; ++k)
        ok = ok && std::fabs(pixel[k] - e.mean[k]) <=
                       6.0 * std::sqrt(v[k]) + 2e-3 * std::fabs(e.mean[k]) + 1e-4;
      if (!ok && ++a.smooth_mismatch <= 5)
        examples << "  pixel (" << x << ", " << y << "): (" << pixel.x << ", " << pixel.y << ", "
                 << pixel.z << "), expected (" << e.mean.x << ", " << e.mean.y << ", " << e.mean.z
                 << ")\n";
    }
  for (int k = 0; k < 3; ++k)
    a.z[k] = variance[k] > 0.0 ? difference[k] / std::sqrt(variance[k])
                               : (std::fabs(difference[k]) < 1e-4 * a.known ? 0.0 : 1e9);
  a.examples = examples.str();
  return a;
}

/// CHECKs an agreement: no smooth pixel off, the sum within 5 standard errors, and at least
/// `min_known` pixels compared.
inline void check_agreement(const Agreement& a, int min_known) {
  INFO(a.known << " pixels predicted, " << a.smooth << " smooth; z = (" << a.z.x << ", " << a.z.y
               << ", " << a.z.z << ")\n"
               << a.examples);
  CHECK(a.known >= min_known);
  CHECK(a.smooth_mismatch == 0);
  CHECK(std::fabs(a.z.x) < 5.0);
  CHECK(std::fabs(a.z.y) < 5.0);
  CHECK(std::fabs(a.z.z) < 5.0);
}

/// Compares `film` with the model's prediction for the same settings and
/// variant over the selected pixels (all if none selected), and CHECKs the agreement.
inline void check_matches_model(const Film& film, const SceneModel& model,
                                const RenderSettings& settings, const VariantModel& variant,
                                int min_known,
                                const std::function<bool(int, int)>& select = nullptr) {
  check_agreement(compare_with_model(film, expected_image(model, settings, variant, select),
                                     settings.samples_per_pixel, select),
                  min_known);
}

/// The index of the n-th sphere (from 0) of the scene that is not a wall (radius under 1000).
inline int small_sphere(const SceneDescription& d, int n = 0) {
  for (std::size_t i = 0; i < d.spheres.size(); ++i)
    if (d.spheres[i].radius < 1000.0f && n-- == 0) return int(i);
  FAIL("the scene has too few spheres");
  return -1;
}

/// The first sphere met by the ray through the centre of pixel (x, y), or -1; with
/// `whole_footprint`, -1 unless every point of the pixel's footprint meets the same sphere.
inline int sphere_seen(const SceneModel& model, const RenderSettings& settings,
                       const VariantModel& variant, int x, int y, bool whole_footprint) {
  const Pinhole camera(model.description().camera, settings.width, settings.height);
  const auto first = [&](double dx, double dy) {
    const std::optional<Hit> hit =
        model.cast(camera.eye(), camera.direction(x + 0.5 + dx, y + 0.5 + dy));
    return hit ? hit->sphere : -1;
  };
  const int sphere = first(0.0, 0.0);
  if (whole_footprint)
    for (const Vec2& p : footprint_ring(variant, settings.antialias_sigma))
      if (first(p.x, p.y) != sphere) return -1;
  return sphere;
}

/// Where the ray through the centre of pixel (x, y) first meets the scene.
inline std::optional<Hit> centre_hit(const SceneModel& model, const RenderSettings& settings, int x,
                                     int y) {
  const Pinhole camera(model.description().camera, settings.width, settings.height);
  return model.cast(camera.eye(), camera.direction(x + 0.5, y + 0.5));
}

/// Chromaticity: the colour divided by the sum of its components.
inline Vec3d chroma(const Vec3d& c) {
  const double sum = c.x + c.y + c.z;
  return sum > 0.0 ? c / sum : Vec3d(1.0 / 3.0);
}

inline double chroma_distance(const Vec3d& a, const Vec3d& b) {
  return glm::length(chroma(a) - chroma(b));
}

/// Pixels whose footprint (within 3 sigma) shows the same diffuse surface through
/// `min_bounces` or more mirror or glass bounces, grouped by the colour they should show (the
/// surface's colour times the mirror and glass colours on the way) and by whether the path
/// crosses glass.
struct HueGroup {
  Vec3d expected{0.0};
  bool through_glass = false;
  Vec3d sum{0.0};
  int pixels = 0;
  std::string surface;  ///< e.g. "sphere 3 (line 25)"
};

inline std::vector<HueGroup> hue_groups(const SceneModel& model, const Film& film,
                                        const RenderSettings& settings, const VariantModel& variant,
                                        int min_bounces) {
  const Pinhole camera(model.description().camera, settings.width, settings.height);
  // Within 3 sigma: all but 1% of the samples, which cannot move a group's hue far.
  std::vector<Vec2> probes = footprint_ring(variant, settings.antialias_sigma, 3.0f);
  std::vector<HueGroup> groups;
  for (int y = 0; y < settings.height; ++y)
    for (int x = 0; x < settings.width; ++x) {
      const std::optional<SeenSurface> seen =
          model.seen_surface(camera.eye(), camera.direction(x + 0.5, y + 0.5));
      if (!seen || seen->specular_bounces < min_bounces) continue;
      bool stable = true;
      for (const Vec2& p : probes) {
        const std::optional<SeenSurface> s =
            model.seen_surface(camera.eye(), camera.direction(x + 0.5 + p.x, y + 0.5 + p.y));
        stable = stable && s && s->key == seen->key;
      }
      if (!stable) continue;
      const Vec3d expected = seen->albedo_color * seen->filter;
      auto group = std::find_if(groups.begin(), groups.end(), [&](const HueGroup& g) {
        return g.through_glass == seen->through_glass &&
               chroma_distance(g.expected, expected) < 1e-9;
      });
      if (group == groups.end()) {
        std::ostringstream name;
        name << "sphere " << seen->sphere << " (line "
             << model.description().spheres[std::size_t(seen->sphere)].line << ")"
             << (seen->through_glass ? " through glass" : "");
        groups.push_back({expected, seen->through_glass, Vec3d(0.0), 0, name.str()});
        group = groups.end() - 1;
      }
      group->sum += to_double(film.at(x, y));
      ++group->pixels;
    }
  return groups;
}

/// Every diffuse colour the scene can show (octant palette included): the hues a group is
/// told apart from.
inline std::vector<Vec3d> scene_colors(const SceneDescription& d) {
  std::vector<Vec3d> colors;
  for (const SphereDescription& s : d.spheres) {
    if (!(s.material.diffuse > 0.0f)) continue;
    if (s.shading == ShadingKind::octants)
      for (const auto& p : kOctantPalette)
        colors.push_back(to_double(s.material.diffuse_color) * Vec3d(p[0], p[1], p[2]));
    else
      colors.push_back(to_double(s.material.diffuse_color));
  }
  return colors;
}

inline std::string describe(const HueGroup& g) {
  const Vec3d mean = g.sum / double(g.pixels);
  std::ostringstream text;
  text << g.pixels << " pixels showing " << g.surface << " of colour (" << g.expected.x << ", "
       << g.expected.y << ", " << g.expected.z << "): mean (" << mean.x << ", " << mean.y << ", "
       << mean.z << ")";
  return text.str();
}

/// CHECKs the groups of at least `min_pixels` pixels; returns how many there are.
///  - Every two groups that should differ clearly in hue (chromaticity distance over 0.15)
///    differ the right way: the difference of their mean chromaticities, projected on the
///    expected difference, is at least a tenth of it. This holds for glass too, whose own
///    reflections of the room add about the same light to every group.
///  - A group seen through mirrors alone has its surface's hue: its mean chromaticity is
///    nearer to the expected one than to that of any other colour of the scene (or group)
///    with a clearly different hue (distance over 0.1).
inline int check_hues(const std::vector<HueGroup>& all, const SceneDescription& d,
                      int min_pixels = 10) {
  std::vector<HueGroup> groups;
  for (const HueGroup& g : all)
    if (g.pixels >= min_pixels) groups.push_back(g);
  for (std::size_t i = 0; i < groups.size(); ++i)
    for (std::size_t j = i + 1; j < groups.size(); ++j) {
      const Vec3d expected = chroma(groups[i].expected) - chroma(groups[j].expected);
      if (glm::length(expected) <= 0.15) continue;
      const Vec3d measured = chroma(groups[i].sum) - chroma(groups[j].sum);
      INFO(describe(groups[i]) << "\nversus " << describe(groups[j]));
      CHECK(glm::dot(measured, expected) >= 0.1 * glm::dot(expected, expected));
    }
  std::vector<Vec3d> candidates = scene_colors(d);
  for (const HueGroup& g : groups)
    candidates.push_back(g.expected);
  for (const HueGroup& g : groups) {
    const Vec3d mean = g.sum / double(g.pixels);
    CHECK(mean.x + mean.y + mean.z > 0.0);
    if (g.through_glass) continue;
    const double own = chroma_distance(mean, g.expected);
    std::string nearer;
    for (const Vec3d& c : candidates)
      if (chroma_distance(c, g.expected) > 0.1 && chroma_distance(mean, c) <= own) {
        std::ostringstream text;
        text << "(" << c.x << ", " << c.y << ", " << c.z << ")";
        nearer = text.str();
      }
    INFO(describe(g) << ", nearer in hue to " << nearer);
    CHECK(nearer.empty());
  }
  return int(groups.size());
}

}  // namespace glint::test
