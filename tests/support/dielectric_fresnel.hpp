#pragma once
// The exact Fresnel reflectance of a dielectric in double, written out from the textbook
// equations independently of glint's policies: the reference models of the tests use it.

#include <algorithm>
#include <cmath>

namespace glint_test {

/// The unpolarised reflectance (the mean of the s and p reflectances) for light meeting the
/// interface at cosine `cos_i` from the side of index `eta_i`; one at total internal reflection.
inline double dielectric_fresnel(double cos_i, double eta_i, double eta_t) {
  const double sin_t = eta_i / eta_t * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
  if (sin_t >= 1.0) return 1.0;
  const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
  const double rs = (eta_i * cos_i - eta_t * cos_t) / (eta_i * cos_i + eta_t * cos_t);
  const double rp = (eta_t * cos_i - eta_i * cos_t) / (eta_t * cos_i + eta_i * cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

}  // namespace glint_test
