#pragma once
// A Trowbridge-Reitz (GGX) mirror and a rough dielectric interface written out in double from the
// textbook forms (Walter et al. 2007, Heitz 2014), independently of glint's single-precision
// code: f cos of the mirror for a Fresnel of one and its directional albedo, by the midpoint rule
// over the hemisphere; the physical BSDF of the interface, reflection and refraction.

#include <algorithm>
#include <cmath>
#include <numbers>

#include "dielectric_fresnel.hpp"

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

/// The physical BSDF f(i -> o) of a rough interface between index `eta_above` (z > 0) and
/// `eta_below`, for light arriving from unit direction i and leaving along o (both pointing away
/// from the surface), by Walter et al. 2007 (equations 20 and 21) with the GGX distribution and
/// the height-correlated Smith G2: f_r = F D G2 / (4 |i.n| |o.n|) and f_t = |i.h| |o.h| eta_o^2
/// (1 - F) D G2 / (|i.n| |o.n| (eta_i i.h + eta_o o.h)^2). `fresnel`: F is the dielectric's;
/// otherwise one where a facet totally reflects and zero elsewhere.
inline double textbook_rough_dielectric(double alpha, double eta_above, double eta_below,
                                        const Direction& i, const Direction& o, bool fresnel) {
  const bool i_above = i.z > 0.0, o_above = o.z > 0.0;
  const double eta_i = i_above ? eta_above : eta_below;
  const double eta_other = i_above ? eta_below : eta_above;
  const double eta_o = o_above ? eta_above : eta_below;
  Direction h = i_above == o_above
                    ? Direction{i.x + o.x, i.y + o.y, i.z + o.z}
                    : Direction{-(eta_i * i.x + eta_o * o.x), -(eta_i * i.y + eta_o * o.y),
                                -(eta_i * i.z + eta_o * o.z)};
  const double length = std::sqrt(h.x * h.x + h.y * h.y + h.z * h.z);
  const double sign = h.z < 0.0 ? -1.0 : 1.0;
  h = {sign * h.x / length, sign * h.y / length, sign * h.z / length};
  const auto dot = [](const Direction& a, const Direction& b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
  };
  const double i_h = dot(i, h), o_h = dot(o, h);
  // Each direction on its own side of the facet.
  if ((i_h > 0.0) != i_above || (o_h > 0.0) != o_above) return 0.0;
  const double a2 = alpha * alpha;
  const double spread = h.z * h.z * (a2 - 1.0) + 1.0;
  const double d = a2 / (std::numbers::pi * spread * spread);
  const auto lambda = [&](double c) {
    return (-1.0 + std::sqrt(1.0 + a2 * (1.0 - c * c) / (c * c))) / 2.0;
  };
  const double g2 = 1.0 / (1.0 + lambda(i.z) + lambda(o.z));
  const double c = std::abs(i_h);
  const double reflectance =
      fresnel ? dielectric_fresnel(c, eta_i, eta_other)
              : (eta_i / eta_other * eta_i / eta_other * (1.0 - c * c) >= 1.0 ? 1.0 : 0.0);
  if (i_above == o_above) return reflectance * d * g2 / (4.0 * std::abs(i.z) * std::abs(o.z));
  const double denominator = eta_i * i_h + eta_o * o_h;
  return std::abs(i_h) * std::abs(o_h) * eta_o * eta_o * (1.0 - reflectance) * d * g2 /
         (std::abs(i.z) * std::abs(o.z) * denominator * denominator);
}

}  // namespace glint_test
