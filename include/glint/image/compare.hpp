#pragma once
// How far a render is from a reference: the RMSE of the whole image (glint-compare-images, the
// variant quality study of bench/run-all, glint-compare's tables) and the per-pixel relative
// squared error that glint-compare's error maps show.

#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <vector>

#include "glint/image/film.hpp"
#include "glint/instruction_set.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The error of one image against a reference, over every pixel and channel of the linear
/// radiance. Values that are NaN or infinite in either image are left out of the sums and
/// counted in `non_finite`; a caller should treat any as an error, not as a small one.
struct ImageComparison {
  double rmse = 0.0;
  /// The reference's mean value over pixels and channels.
  double mean_reference = 0.0;
  std::size_t non_finite = 0;

  /// rmse divided by the reference's mean, so that scenes of different brightness compare;
  /// NaN for a black reference, which has no relative error.
  double relative_rmse() const {
    return mean_reference > 0.0 ? rmse / mean_reference : std::numeric_limits<double>::quiet_NaN();
  }
};

/// Throws std::invalid_argument if the images differ in size.
inline ImageComparison compare_images(const Film& test, const Film& reference) {
  if (test.width() != reference.width() || test.height() != reference.height())
    throw std::invalid_argument("compare_images: the images differ in size");
  // Sums in double: a million pixels of float squares would lose digits in float.
  double squared_error = 0.0;
  double reference_sum = 0.0;
  ImageComparison result;
  for (std::size_t i = 0; i < test.pixels().size(); ++i) {
    const Color& a = test.pixels()[i];
    const Color& b = reference.pixels()[i];
    for (int c = 0; c < 3; ++c) {
      const double x = a[c];
      const double y = b[c];
      if (!std::isfinite(x) || !std::isfinite(y)) {
        ++result.non_finite;
        continue;
      }
      squared_error += (x - y) * (x - y);
      reference_sum += y;
    }
  }
  const double values = 3.0 * double(test.pixels().size());
  result.rmse = std::sqrt(squared_error / values);
  result.mean_reference = reference_sum / values;
  return result;
}

/// The default epsilon of relative_squared_error: without it a pixel that is black in the
/// reference would have an infinite error; 0.01 is the value common in the denoising
/// literature (relMSE), small next to the radiance of a lit surface.
inline constexpr double kRelativeErrorEpsilon = 0.01;

/// Per pixel (row-major, as Film::pixels), the mean over the three channels of
/// (x - r)^2 / (r^2 + epsilon): an error that reads the same in dark and bright regions, as
/// the eye judges noise. NaN where any channel of either image is not finite. Throws
/// std::invalid_argument if the images differ in size.
inline std::vector<float> relative_squared_error(const Film& test, const Film& reference,
                                                 double epsilon = kRelativeErrorEpsilon) {
  if (test.width() != reference.width() || test.height() != reference.height())
    throw std::invalid_argument("relative_squared_error: the images differ in size");
  std::vector<float> errors(test.pixels().size());
  for (std::size_t i = 0; i < errors.size(); ++i) {
    const Color& a = test.pixels()[i];
    const Color& b = reference.pixels()[i];
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) {
      const double x = a[c];
      const double r = b[c];
      sum += (x - r) * (x - r) / (r * r + epsilon);
    }
    // Float values squared stay far inside the double range, so only a non-finite input
    // makes the sum non-finite (NaN or infinite); both read as NaN, "no error known".
    errors[i] = std::isfinite(sum) ? static_cast<float>(sum / 3.0)
                                   : std::numeric_limits<float>::quiet_NaN();
  }
  return errors;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
