#pragma once
// A Trowbridge-Reitz (GGX) mirror written out in double from the textbook forms (Walter et al.
// 2007, Heitz 2014), independently of glint's single-precision code: f cos for a Fresnel of one
// and the directional albedo, by the midpoint rule over the hemisphere.

#include <cmath>
#include <numbers>

namespace glint_test {

struct Direction {
  double x, y, z;
};

/// f(wo, wi) cos(wi) of a Trowbridge-Reitz mirror of width `alpha` with a Fresnel of one (both
/// directions unit, above the surface, z up): D = 1 / (pi alpha^2 cos^4 (1 + tan^2 / alpha^2)^2),
/// Lambda = (-1 + sqrt(1 + alpha^2 tan^2)) / 2, f = D G2 / (4 cos_o cos_i).
inline double textbook_ggx_f_cos(double alpha, const Direction& wo, const Direction& wi) {
  const double hx = wo.x + wi.x, hy = wo.y + wi.y, hz = wo.z + wi.z;
  const double cos_h = hz / std::sqrt(hx * hx + hy * hy + hz * hz);
  const double cos2 = cos_h * cos_h, tan2 = (1.0 - cos2) / cos2;
  const double spread = 1.0 + tan2 / (alpha * alpha);
  const double d = 1.0 / (std::numbers::pi * alpha * alpha * cos2 * cos2 * spread * spread);
  const auto lambda = [&](double c) {
    return (-1.0 + std::sqrt(1.0 + alpha * alpha * (1.0 - c * c) / (c * c))) / 2.0;
  };
  return d / (1.0 + lambda(wo.z) + lambda(wi.z)) / (4.0 * wo.z);
}

/// The integral of g(direction) over the upper hemisphere by the midpoint rule in (theta, phi)
/// on an n x 4n grid: even in theta, so that a narrow lobe around the normal gets as many steps
/// as one elsewhere.
template <typename G>
double hemisphere_integral(G&& g, int n) {
  const double d_theta = 0.5 * std::numbers::pi / n, d_phi = 2.0 * std::numbers::pi / (4 * n);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double theta = (i + 0.5) * d_theta;
    const double c = std::cos(theta), s = std::sin(theta);
    double ring = 0.0;
    for (int j = 0; j < 4 * n; ++j) {
      const double phi = (j + 0.5) * d_phi;
      ring += g(Direction{s * std::cos(phi), s * std::sin(phi), c});
    }
    sum += ring * s;
  }
  return sum * d_theta * d_phi;
}

/// The directional albedo of the mirror for light leaving at angle theta_o from the normal.
inline double textbook_ggx_albedo(double alpha, double theta_o, int n = 2000) {
  const Direction wo{std::sin(theta_o), 0.0, std::cos(theta_o)};
  return hemisphere_integral([&](const Direction& wi) { return textbook_ggx_f_cos(alpha, wo, wi); },
                             n);
}

}  // namespace glint_test
