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
};

namespace detail {
inline void set_surface_lane(SurfaceLanes<float>& to, int, const SurfaceProperties& s) {
  const Material& m = s.material;
  to = {m.diffuse,      m.diffuse_color,     m.mirror,
        m.mirror_color, m.transparent,       m.transparent_color,
        m.ior,          m.emission,          s.center,
        s.ior_outside,  s.fully_transparent, std::int32_t(s.shading),
        s.emitter};
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
    // The 88 bytes of SurfaceProperties, read as 22 words: the material's seventeen floats, the
    // centre, ior_outside, a word whose two low bytes are the shading kind and
    // fully_transparent (and whose two high bytes are padding), and the emitter's index. They
    // are loaded in three blocks of eight consecutive words (the last two overlapping) for all
    // the lanes at once, transposed in registers.
    constexpr int kRecordWords = 22;
    static_assert(offsetof(SurfaceProperties, material) == 0 && offsetof(Material, diffuse) == 0 &&
                  offsetof(Material, diffuse_color) == 4 && offsetof(Material, mirror) == 16 &&
                  offsetof(Material, mirror_color) == 20 && offsetof(Material, transparent) == 32 &&
                  offsetof(Material, transparent_color) == 36 && offsetof(Material, ior) == 48 &&
                  offsetof(Material, emission) == 52 && offsetof(SurfaceProperties, center) == 64 &&
                  offsetof(SurfaceProperties, ior_outside) == 76 &&
                  offsetof(SurfaceProperties, shading) == 80 && sizeof(ShadingKind) == 1 &&
                  offsetof(SurfaceProperties, fully_transparent) == 81 && sizeof(bool) == 1 &&
                  offsetof(SurfaceProperties, emitter) == 84 &&
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
    s.center = {last[2], last[3], last[4]};
    s.ior_outside = last[5];
    const auto flags = std::bit_cast<IntFor<F>>(last[6]);
    s.shading = flags & 0xff;
    s.fully_transparent = (flags & 0xff00) != 0;
    s.emitter = select(lanes, std::bit_cast<UIntFor<F>>(last[7]), splat<UIntFor<F>>(kNotAnEmitter));
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
         both(low.emitter, high.emitter)};
#endif
  } else {
    for (int i = 0; i < W; ++i)
      if (lanes[i]) detail::set_surface_lane(s, i, scene.surface(sphere[i]));
  }
  return s;
}

}  // namespace glint::inline GLINT_ISA_NAMESPACE
