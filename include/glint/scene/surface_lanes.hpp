#pragma once
// The properties of the spheres that a Float's lanes of hits met, as the shading step reads
// them: one sphere's SurfaceProperties at width 1, a column per field wider.

#include <bit>
#include <cstddef>
#include <cstdint>

#include "glint/instruction_set.hpp"
#include "glint/math/lanes.hpp"
#include "glint/math/wide.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// SurfaceProperties lane by lane (lane i: the sphere of hit i).
template <typename F>
struct SurfaceLanes {
  using V3 = Vec3For<F>;
  F diffuse;
  V3 diffuse_color;
  F mirror;
  V3 mirror_color;
  F transparent;
  V3 transparent_color;
  F ior;
  V3 emission;
  V3 center;
  F ior_outside;
  MaskFor<F> fully_transparent;
  IntFor<F> shading;   ///< the ShadingKind
  UIntFor<F> emitter;  ///< index in Scene::emitters(), or kNotAnEmitter
  /// The mirror lobe's finish, read only for the lanes of `mirror_finish` (zero elsewhere).
  MaskFor<F> mirror_finish;
  F mirror_roughness;
  V3 metal_eta;
  V3 metal_k;
  F transparent_roughness;  ///< the transparent lobe's interface (Material's, every lane)
};

namespace detail {
inline void set_surface_lane(SurfaceLanes<float>& to, int, const SurfaceProperties& s) {
  const Material& m = s.material;
  to = {m.diffuse,
        m.diffuse_color,
        m.mirror,
        m.mirror_color,
        m.transparent,
        m.transparent_color,
        m.ior,
        m.emission,
        s.center,
        s.ior_outside,
        s.fully_transparent,
        std::int32_t(s.shading),
        s.emitter,
        s.mirror_finish,
        s.mirror_finish ? m.mirror_roughness : 0.0f,
        s.mirror_finish ? m.metal_eta : Color(0.0f),
        s.mirror_finish ? m.metal_k : Color(0.0f),
        m.transparent_roughness};
}
template <typename F>
void set_surface_lane(SurfaceLanes<F>& to, int i, const SurfaceProperties& s) {
  const Material& m = s.material;
  to.diffuse[i] = m.diffuse;
  to.diffuse_color.set_lane(i, m.diffuse_color);
  to.mirror[i] = m.mirror;
  to.mirror_color.set_lane(i, m.mirror_color);
  to.transparent[i] = m.transparent;
  to.transparent_color.set_lane(i, m.transparent_color);
  to.ior[i] = m.ior;
  to.emission.set_lane(i, m.emission);
  to.center.set_lane(i, s.center);
  to.ior_outside[i] = s.ior_outside;
  to.fully_transparent[i] = s.fully_transparent ? -1 : 0;
  to.shading[i] = std::int32_t(s.shading);
  to.emitter[i] = s.emitter;
  to.transparent_roughness[i] = m.transparent_roughness;
  if (s.mirror_finish) {
    to.mirror_finish[i] = -1;
    to.mirror_roughness[i] = m.mirror_roughness;
    to.metal_eta.set_lane(i, m.metal_eta);
    to.metal_k.set_lane(i, m.metal_k);
  }
}
}  // namespace detail

/// The properties of spheres `sphere` in the lanes of `lanes`; the other lanes read as a sphere
/// of zeros (no lobe, no emission, not an emitter).
template <FloatType F>
SurfaceLanes<F> gather_surfaces(const Scene& scene, UIntFor<F> sphere, MaskFor<F> lanes) {
  constexpr int W = kLanesOf<F>;
  SurfaceLanes<F> s{};
  s.emitter = splat<UIntFor<F>>(kNotAnEmitter);
  if constexpr (W == 1) {
    if (lanes) detail::set_surface_lane(s, 0, scene.surface(sphere));
#if defined(GLINT_AVX2)
  } else if constexpr (W == kLaneCount || W == kMaxColumnRows) {
    // The 120 bytes of SurfaceProperties, read as 30 words: the material's sixteen floats of
    // the report's lobes, seven of the mirror's finish and the transparent lobe's roughness, the
    // centre, ior_outside, a word whose three low bytes are the shading kind, fully_transparent
    // and mirror_finish (and whose high byte is padding), and the emitter's index. The report's
    // words are loaded in three blocks of eight consecutive words (the first sixteen, and the
    // last eight, which begin with the finish's last word and the transparent roughness) for all
    // the lanes at once, transposed in registers; the finish's block only where a lane has one.
    constexpr int kRecordWords = 30;
    static_assert(offsetof(SurfaceProperties, material) == 0 && offsetof(Material, diffuse) == 0 &&
                  offsetof(Material, diffuse_color) == 4 && offsetof(Material, mirror) == 16 &&
                  offsetof(Material, mirror_color) == 20 && offsetof(Material, transparent) == 32 &&
                  offsetof(Material, transparent_color) == 36 && offsetof(Material, ior) == 48 &&
                  offsetof(Material, emission) == 52 &&
                  offsetof(Material, mirror_roughness) == 64 &&
                  offsetof(Material, metal_eta) == 68 && offsetof(Material, metal_k) == 80 &&
                  offsetof(Material, transparent_roughness) == 92 &&
                  offsetof(SurfaceProperties, center) == 96 &&
                  offsetof(SurfaceProperties, ior_outside) == 108 &&
                  offsetof(SurfaceProperties, shading) == 112 && sizeof(ShadingKind) == 1 &&
                  offsetof(SurfaceProperties, fully_transparent) == 113 && sizeof(bool) == 1 &&
                  offsetof(SurfaceProperties, mirror_finish) == 114 &&
                  offsetof(SurfaceProperties, emitter) == 116 &&
                  sizeof(SurfaceProperties) == kRecordWords * sizeof(float));
    static constexpr float kNoSurface[kRecordWords] = {};
    const float* record[W];
    for (int i = 0; i < W; ++i)
      record[i] = lanes[i] ? reinterpret_cast<const float*>(&scene.surface(sphere[i])) : kNoSurface;
    F first[kLaneCount], second[kLaneCount], last[kLaneCount];
    const auto load_block = [&](int offset, F(&columns)[kLaneCount]) {
      const float* rows[W];
      for (int i = 0; i < W; ++i)
        rows[i] = record[i] + offset;
      load_columns(rows, columns);
    };
    load_block(0, first);
    load_block(8, second);
    load_block(kRecordWords - 8, last);
    s.diffuse = first[0];
    s.diffuse_color = {first[1], first[2], first[3]};
    s.mirror = first[4];
    s.mirror_color = {first[5], first[6], first[7]};
    s.transparent = second[0];
    s.transparent_color = {second[1], second[2], second[3]};
    s.ior = second[4];
    s.emission = {second[5], second[6], second[7]};
    s.transparent_roughness = last[1];
    s.center = {last[2], last[3], last[4]};
    s.ior_outside = last[5];
    const auto flags = std::bit_cast<IntFor<F>>(last[6]);
    s.shading = flags & 0xff;
    s.fully_transparent = (flags & 0xff00) != 0;
    s.mirror_finish = (flags & 0xff0000) != 0;
    s.emitter = select(lanes, std::bit_cast<UIntFor<F>>(last[7]), splat<UIntFor<F>>(kNotAnEmitter));
    if (any(s.mirror_finish)) {
      F finish[kLaneCount];
      load_block(16, finish);
      const F zero = splat<F>(0.0f);
      s.mirror_roughness = select(s.mirror_finish, finish[0], zero);
      s.metal_eta = select(s.mirror_finish, Vector3<F>{finish[1], finish[2], finish[3]},
                           Vector3<F>{zero, zero, zero});
      s.metal_k = select(s.mirror_finish, Vector3<F>{finish[4], finish[5], finish[6]},
                         Vector3<F>{zero, zero, zero});
    }
  } else if constexpr (W == 2 * kLaneCount) {
    // Two transposes of eight.
    const SurfaceLanes<FloatLanes> low =
        gather_surfaces<FloatLanes>(scene, low_half(sphere), low_half(lanes));
    const SurfaceLanes<FloatLanes> high =
        gather_surfaces<FloatLanes>(scene, high_half(sphere), high_half(lanes));
    const auto both = [](const auto& a, const auto& b) { return join(a, b); };
    const auto both3 = [](const Vec3Lanes& a, const Vec3Lanes& b) {
      return Vector3<F>{join(a.x, b.x), join(a.y, b.y), join(a.z, b.z)};
    };
    s = {both(low.diffuse, high.diffuse),
         both3(low.diffuse_color, high.diffuse_color),
         both(low.mirror, high.mirror),
         both3(low.mirror_color, high.mirror_color),
         both(low.transparent, high.transparent),
         both3(low.transparent_color, high.transparent_color),
         both(low.ior, high.ior),
         both3(low.emission, high.emission),
         both3(low.center, high.center),
         both(low.ior_outside, high.ior_outside),
         both(low.fully_transparent, high.fully_transparent),
         both(low.shading, high.shading),
         both(low.emitter, high.emitter),
         both(low.mirror_finish, high.mirror_finish),
         both(low.mirror_roughness, high.mirror_roughness),
         both3(low.metal_eta, high.metal_eta),
         both3(low.metal_k, high.metal_k),
         both(low.transparent_roughness, high.transparent_roughness)};
#endif
  } else {
    for (int i = 0; i < W; ++i)
      if (lanes[i]) detail::set_surface_lane(s, i, scene.surface(sphere[i]));
  }
  return s;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
