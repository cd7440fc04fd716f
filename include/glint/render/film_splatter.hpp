#pragma once
// Light that lands anywhere on the film (a light path joined to the camera) spread onto the
// pixels whose filters cover the point: the pixel filter is the distribution of a pixel's camera
// rays (policy/antialiasing.hpp), so a pixel takes a splat in proportion to its filter's density
// at the splat's offset from its centre. The sums are fixed point (image/splat_sums.hpp), the
// same bits in any order.

#include <cmath>

#include "glint/config.hpp"
#include "glint/image/splat_sums.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/vector.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/render_settings.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Splats onto a film of the settings' size with Config C's pixel filter, each weighted
/// 1 / (width x height) for the light paths of one sample per pixel.
template <RenderConfig C>
class FilmSplatter {
 public:
  /// `camera`'s film (kept by reference): where it wraps around, light landing near an edge also
  /// lands where the film continues past it (Camera::film_images).
  FilmSplatter(const RenderSettings& settings, const Camera& camera)
      : camera_(camera),
        width_(settings.width),
        height_(settings.height),
        sigma_(settings.antialias_sigma),
        footprint_(C::antialiasing::footprint(settings.antialias_sigma)),
        per_path_(1.0f / (float(settings.width) * float(settings.height))) {}

  /// Whether the filter has an area: without one (every camera ray through a pixel's centre) no
  /// splat lands on a pixel.
  bool has_area() const { return footprint_ > 0.0f; }

  /// `light` landing at film position `film`, on every pixel whose filter covers it, weighted by
  /// the filter's density h there, by weight(h) and by 1 / (width x height). A value that is not
  /// finite or beyond the sums' range is counted as invalid instead.
  template <typename Weight>
  void add(SplatSums& splats, Vec2 film, const Color& light, Weight&& weight,
           TraceCounters& counters) const {
    if (!(std::isfinite(light.r) && std::isfinite(light.g) && std::isfinite(light.b))) {
      ++counters.invalid_samples;
      return;
    }
    // Every film point that shows the same direction near the film (a panorama's film wraps
    // around): the pixels' filters reach it there too.
    camera_.film_images(film, footprint_ + 1.0f,
                        [&](Vec2 image) { add_at(splats, image, light, weight, counters); });
  }

 private:
  /// add, for the film as a plane.
  template <typename Weight>
  void add_at(SplatSums& splats, Vec2 film, const Color& light, Weight& weight,
              TraceCounters& counters) const {
    // The pixels whose centres (x + 0.5, y + 0.5) lie within the footprint of the point.
    const float x_low = std::ceil(film.x - 0.5f - footprint_);
    const float x_high = std::floor(film.x - 0.5f + footprint_);
    const float y_low = std::ceil(film.y - 0.5f - footprint_);
    const float y_high = std::floor(film.y - 0.5f + footprint_);
    if (!(x_high >= 0.0f && y_high >= 0.0f && x_low < float(width_) && y_low < float(height_)))
      return;
    const int x0 = int(std::fmax(x_low, 0.0f));
    const int x1 = int(std::fmin(x_high, float(width_ - 1)));
    const int y0 = int(std::fmax(y_low, 0.0f));
    const int y1 = int(std::fmin(y_high, float(height_ - 1)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const Vec2 offset(film.x - (float(x) + 0.5f), film.y - (float(y) + 0.5f));
        const float density = C::antialiasing::density(offset, sigma_);
        if (!(density > 0.0f)) continue;
        const Color value = light * (density * weight(density) * per_path_);
        if (SplatSums::representable(value))
          splats.add(x, y, value);
        else
          ++counters.invalid_samples;
      }
  }

  const Camera& camera_;
  int width_, height_;
  float sigma_;
  float footprint_;
  float per_path_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
