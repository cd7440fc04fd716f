#pragma once
// Bidirectional path tracing (Veach and Guibas 1995; Veach's thesis, chapter 10): for each
// sample a camera subpath z_0 (the camera), z_1, ... and a light subpath y_0 (a point on a light),
// y_1, ..., and every way of joining them: a full path of s light vertices and t camera vertices
// (a "strategy (s, t)") is
//   s = 0   the camera subpath reaching an emissive sphere by itself,
//   s = 1   a camera vertex joined to a point drawn on a light (next-event estimation),
//   t = 1   a light vertex joined to the camera (light tracing: a splat on the pixels that see it),
//   s, t >= 2  a light vertex joined to a camera vertex by a shadow ray.
// A path of k scattering vertices can come from k + 2 such strategies; each contribution is
// weighted by the power heuristic over all the strategies that could have made the same path, so
// that a caustic comes from light tracing, a lamp's direct light from next-event estimation and a
// small lamp seen in a mirror from the camera subpath, each where it samples best.
//
// Joins need a vertex whose Bsdf has a density (render/bsdf.hpp; the report's diffuse lobe), and
// each vertex keeps its Bsdf's record to be evaluated when joined. Mirror and refraction vertices
// are deltas, passed through by the subpaths; point lights are deltas of
// position, reached only by joins; the camera is a pinhole, reached only by joins. The
// background, a colour or an image that is not black, is a light infinitely far away
// (render/lights/environment_light.hpp): a camera subpath that escapes ends on it, joins reach it
// by a direction, and light subpaths leave it through a disc facing that direction; its vertex
// stands for the direction (PathVertexKind::environment).
//
// Densities are per unit area at the vertex they produce (per unit solid angle converted by
// |cos| / distance^2), as pbrt-v4's BDPT keeps them; a vertex produced through a delta keeps no
// density (zero, read as one in the ratios, where the delta cancels). The camera's density for a
// direction is its pixel filter's density at the film point over width x height (the light
// paths per sample that could have splatted there), so that light tracing's weight in a pixel
// follows the filter; a filter without an area (pixel centres) gives light tracing no weight,
// and no light path is joined to the camera.
//
// Path length is counted as every estimator counts it (render/estimators/path_context.hpp): at
// most max_depth + 1 scattering vertices between a light and the camera, s + t - 2 of them for
// strategy (s, t).

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>
#include <type_traits>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/math/octahedral_direction.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/light.hpp"
#include "glint/render/light_selection.hpp"
#include "glint/render/materials.hpp"
#include "glint/render/scattering.hpp"
#include "glint/render/scene_lights.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// What a vertex of a subpath is: the camera, a light at a point (which only sampling finds), a
/// light with a surface, a surface that scatters, or the environment: a light infinitely far
/// away, whose vertex stands for a direction (as pbrt-v4's BDPT keeps its infinite lights). On a
/// camera subpath it is where an escaping ray meets the image; its `point` lies one unit along
/// that ray and `facing` holds the ray's direction. On a light subpath it is the point of the
/// disc the light path started from (EnvironmentLight::sample_le).
enum class PathVertexKind : std::uint8_t { camera, delta_light, area_light, surface, environment };

/// A vertex of a camera or a light subpath; `Record` is the material's record of its Bsdf there
/// (RecordableBsdf), which the weights below never read.
template <typename Record>
struct BasicPathVertex {
  using Kind = PathVertexKind;
  Kind kind = Kind::surface;
  Vec3 point{0.0f};
  /// The sphere's outward normal at the point; zero for the camera and a light at a point.
  Vec3 normal{0.0f};
  /// The normal on the side the subpath arrived from (a surface).
  Vec3 facing{0.0f};
  std::uint32_t sphere = kNoSphere;
  /// The light a light vertex lies on.
  LightId light = 0;
  /// The subpath's weight at the vertex: what it carries there over the densities of the
  /// choices that made it (emitted radiance or importance, times f |cos| / pdf at each vertex
  /// before).
  Color beta{0.0f};
  /// The material at a surface, as the subpath's Bsdf recorded it (none where it does not
  /// scatter: no join can use the vertex).
  Record scattering{};
  /// The subpath went on from here through a mirror or refraction: no other strategy could
  /// have chosen its next vertex.
  bool delta = false;
  /// Density of this vertex as its subpath produced it, per unit area (for the first light
  /// vertex: the light's probability, per unit area on a sphere); zero behind a delta.
  float pdf_forward = 0.0f;
  /// Density of this vertex had the other subpath produced it, per unit area.
  float pdf_reverse = 0.0f;
  /// For vertex merging: what the other strategies' squared density ratios over this vertex and
  /// those before it on its subpath add to a weight's denominator, per unit of the squared ratio
  /// at this vertex (detail::strategy_tails). Set once the subpath is complete.
  float strategy_tail = 0.0f;

  bool is_light() const {
    return kind == Kind::delta_light || kind == Kind::area_light || kind == Kind::environment;
  }
  /// Whether a join may end at this vertex: it scatters (or emits, or sees) in every direction.
  bool joinable() const { return kind != Kind::surface || scattering.has_density(); }
};

/// The vertices of Config C's subpaths.
template <typename C>
using PathVertexOf = BasicPathVertex<typename BsdfAt<C>::Record>;

namespace detail {

/// Density per unit area at `to` of a direction from `from` of density `solid_angle_pdf`:
/// |cos| at `to` over the squared distance (no cosine where `to` is not on a surface). Towards
/// the environment, which has no area, the density stays per unit solid angle; from it, the
/// density given is the disc's per unit area (EnvironmentLight::disc_density), and only the
/// cosine at `to` converts it, parallel rays keeping their spacing.
template <typename V>
float area_density(float solid_angle_pdf, const V& from, const V& to) {
  if (to.kind == PathVertexKind::environment) return solid_angle_pdf;
  const Vec3 offset = to.point - from.point;
  if (from.kind == PathVertexKind::environment) {
    const bool on_surface = to.kind == PathVertexKind::surface;
    return on_surface ? solid_angle_pdf * std::fabs(glm::dot(to.normal, glm::normalize(offset)))
                      : solid_angle_pdf;
  }
  const float distance2 = glm::dot(offset, offset);
  if (!(distance2 > 0.0f)) return 0.0f;
  float pdf = solid_angle_pdf / distance2;
  if (to.kind == PathVertexKind::surface || to.kind == PathVertexKind::area_light)
    pdf *= std::fabs(glm::dot(to.normal, offset)) / std::sqrt(distance2);
  return pdf;
}

/// A density ratio's terms with a delta's zero read as one (the delta cancels in the ratio).
inline float nonzero(float pdf) {
  return pdf != 0.0f ? pdf : 1.0f;
}

}  // namespace detail

/// The reverse densities that a join sets on the ends of the subpaths it joins: of the joined
/// vertices (each as the other subpath would have made it) and of the vertices before them (made
/// through the joined ones). Read in place of the vertices' own pdf_reverse; zero where the
/// subpath has no such vertex.
struct JoinDensities {
  float light_end = 0.0f, light_before = 0.0f, camera_end = 0.0f, camera_before = 0.0f;
  /// No light path reaches the camera end (or the vertex before it), which a zero density would
  /// not say (a zero is a delta's, read as one): a point of a huge sphere outside the disc light
  /// paths from the environment enter through. The strategies that would need one do not count.
  bool camera_end_unreachable = false, camera_before_unreachable = false;
};

/// How the strategies that compete for a path are counted.
struct StrategyRules {
  /// Whether the pixel filter has an area, so that joins to the camera (t = 1) land on pixels.
  bool light_tracing_counts = true;
  /// Vertex merging's density factor: pi r^2 x the light paths a camera vertex may merge with
  /// (Georgiev et al. 2012's eta). Zero: no merging strategy (bidirectional path tracing).
  float merge_density = 0.0f;
};

namespace detail {

/// The sum over the strategies other than the join of light[0, s) and camera[0, t) of (their
/// density / the join's)^2: the power heuristic's weight of the join is 1 / (1 + sum). The join's
/// reverse densities come from `join`; the camera end's delta is read as cleared, and so is the
/// light end's where the light end is joined (`light_end_joined`; a merge takes the light subpath
/// up to the vertex before the merged one, whose own scattering is on the path). The ratios are
/// built vertex by vertex from the ends outwards: moving vertex v to the other side multiplies
/// by (its other side's density / its own side's); merging at v, by eta x its other side's
/// density, once v is on the side it was made by.
template <typename V>
float other_strategies(std::span<const V> light, std::span<const V> camera,
                       const JoinDensities& join, const StrategyRules& rules,
                       bool light_end_joined) {
  const std::size_t s = light.size(), t = camera.size();
  const float eta = rules.merge_density;
  const auto camera_reverse = [&](std::size_t i) {
    return i + 1 == t ? join.camera_end : i + 2 == t ? join.camera_before : camera[i].pdf_reverse;
  };
  const auto light_reverse = [&](std::size_t i) {
    return i + 1 == s ? join.light_end : i + 2 == s ? join.light_before : light[i].pdf_reverse;
  };
  const auto camera_delta = [&](std::size_t i) { return i + 1 < t && camera[i].delta; };
  const auto light_delta = [&](std::size_t i) {
    return (i + 1 < s || !light_end_joined) && light[i].delta;
  };
  float sum = 0.0f;
  // Fewer camera vertices: camera[i] made by the light side. Strategy (s + t - i, i).
  float ratio = 1.0f;
  for (std::size_t i = t - 1; i > 0; --i) {
    if ((i + 1 == t && join.camera_end_unreachable) ||
        (i + 2 == t && join.camera_before_unreachable))
      break;
    const float reverse = nonzero(camera_reverse(i));
    // Merging at camera[i]: not at the path's light end (s = 0: camera[t - 1] is on a lamp).
    if (eta > 0.0f && camera[i].kind == PathVertexKind::surface && !camera_delta(i) &&
        (s > 0 || i + 1 < t)) {
      const float merge = ratio * eta * reverse;
      sum += merge * merge;
    }
    ratio *= reverse / nonzero(camera[i].pdf_forward);
    const bool joinable = !camera_delta(i) && !camera_delta(i - 1);
    // The camera cannot be joined to the environment, which lies infinitely far away.
    const bool to_camera_possible =
        i > 1 || (rules.light_tracing_counts && camera[1].kind != PathVertexKind::environment);
    if (joinable && to_camera_possible) sum += ratio * ratio;
  }
  // Fewer light vertices: light[i] made by the camera side. Strategy (i, s + t - i).
  ratio = 1.0f;
  for (std::size_t i = s; i-- > 0;) {
    const float reverse = nonzero(light_reverse(i));
    // Merging at light[i]: not at the light's own point.
    if (eta > 0.0f && i > 0 && light[i].kind == PathVertexKind::surface && !light_delta(i)) {
      const float merge = ratio * eta * reverse;
      sum += merge * merge;
    }
    ratio *= reverse / nonzero(light[i].pdf_forward);
    const bool before_delta =
        i > 0 ? light_delta(i - 1) : light[0].kind == PathVertexKind::delta_light;
    if (!light_delta(i) && !before_delta) sum += ratio * ratio;
  }
  return sum;
}

/// The power heuristic's weight of the join of light[0, s) and camera[0, t) with `join`'s
/// reverse densities.
template <typename V>
float join_weight(std::span<const V> light, std::span<const V> camera, const JoinDensities& join,
                  const StrategyRules& rules) {
  return 1.0f / (1.0f + other_strategies(light, camera, join, rules, true));
}

/// The power heuristic's weight of merging at camera[t - 1] a vertex made by light[s - 1], with
/// `join`'s reverse densities (camera_end: the density with which light[s - 1] made the light
/// vertex).
template <typename V>
float merge_weight(std::span<const V> light, std::span<const V> camera, const JoinDensities& join,
                   const StrategyRules& rules) {
  const float merge = rules.merge_density * nonzero(join.camera_end);
  // The join of light[s - 1] to camera[t - 1] that the ratios are built from is itself a
  // strategy for this path only where light[s - 1] does not go on through a delta.
  const float join_counts = light.back().delta ? 0.0f : 1.0f;
  return merge * merge / (join_counts + other_strategies(light, camera, join, rules, false));
}

/// Sets each vertex's strategy_tail on subpath `v` (light or camera side, by `light_side`),
/// whose densities are its own: the sum that other_strategies' loop over that side adds for
/// v[0..m] when it reaches v[m] with a ratio of one, built from v[m - 1]'s as
///   tail(m) = merge(m) (eta reverse_m)^2 + (reverse_m / forward_m)^2 (join(m) + tail(m - 1)),
/// merge(m) and join(m) being whether merging at v[m] and the join before it are strategies. A
/// merge's weight then needs only the vertices next to it (merge_weight_from_factors). The last
/// vertex's tail is left unset: its reverse density is the join's.
template <typename V>
void strategy_tails(std::span<V> v, bool light_side, const StrategyRules& rules) {
  const float eta = rules.merge_density;
  float tail = 0.0f;
  for (std::size_t m = light_side ? 0 : 1; m + 1 < v.size(); ++m) {
    const float reverse = nonzero(v[m].pdf_reverse);
    const bool merges =
        eta > 0.0f && (!light_side || m > 0) && v[m].kind == PathVertexKind::surface && !v[m].delta;
    const bool joins =
        light_side
            ? !v[m].delta && !(m > 0 ? v[m - 1].delta : v[0].kind == PathVertexKind::delta_light)
            : !v[m].delta && !v[m - 1].delta && (m > 1 || rules.light_tracing_counts);
    const float ratio = reverse / nonzero(v[m].pdf_forward);
    tail = (merges ? (eta * reverse) * (eta * reverse) : 0.0f) +
           ratio * ratio * ((joins ? 1.0f : 0.0f) + tail);
    v[m].strategy_tail = tail;
  }
}

/// What merging at camera[t - 1] adds to the weight's denominator from the camera side, per
/// squared density camera_end (c): c^2 (p + camera_before^2 q). The same for every light vertex
/// merged there.
struct MergeCameraFactors {
  float p = 0.0f, q = 0.0f;
};

/// merge_weight's camera side for merges at camera[t - 1] (t >= 2), from the vertices next to it
/// and camera[t - 3]'s strategy tail (strategy_tails): the terms of other_strategies' camera loop
/// at the merged vertex (its delta cleared) and at the one before, then the tail, each with
/// camera_end and camera_before factored out.
template <typename V>
MergeCameraFactors merge_camera_factors(std::span<const V> camera, const StrategyRules& rules) {
  const std::size_t t = camera.size();
  const float eta2 = rules.merge_density * rules.merge_density;
  const V& end = camera[t - 1];
  const float end_forward2 = nonzero(end.pdf_forward) * nonzero(end.pdf_forward);
  MergeCameraFactors factors;
  if (rules.merge_density > 0.0f && end.kind == PathVertexKind::surface) factors.p = eta2;
  if (!camera[t - 2].delta && (t > 2 || rules.light_tracing_counts))
    factors.p += 1.0f / end_forward2;
  if (t >= 3) {
    const V& before = camera[t - 2];
    float inner = 0.0f;
    if (rules.merge_density > 0.0f && before.kind == PathVertexKind::surface && !before.delta)
      inner = eta2;
    float behind = t >= 4 ? camera[t - 3].strategy_tail : 0.0f;
    if (!before.delta && !camera[t - 3].delta && (t > 3 || rules.light_tracing_counts))
      behind += 1.0f;
    inner += behind / (nonzero(before.pdf_forward) * nonzero(before.pdf_forward));
    factors.q = inner / end_forward2;
  }
  return factors;
}

/// merge_weight's light side for a merge of the vertex that light[s - 1] made: what it adds to
/// the weight's denominator per squared density light_end, from light[s - 1] and
/// light[s - 2]'s strategy tail (strategy_tails).
template <typename V>
float merge_light_factor(std::span<const V> light, const StrategyRules& rules) {
  const std::size_t s = light.size();
  const V& from = light[s - 1];
  float factor = 0.0f;
  if (rules.merge_density > 0.0f && s > 1 && from.kind == PathVertexKind::surface && !from.delta)
    factor = rules.merge_density * rules.merge_density;
  const bool before_delta =
      s > 1 ? light[s - 2].delta : light[0].kind == PathVertexKind::delta_light;
  float behind = s >= 2 ? light[s - 2].strategy_tail : 0.0f;
  if (!from.delta && !before_delta) behind += 1.0f;
  return factor + behind / (nonzero(from.pdf_forward) * nonzero(from.pdf_forward));
}

/// merge_weight from its factors: `join`'s camera_end, camera_before and light_end, the camera
/// side's factors and the light side's, and whether light[s - 1] went on through a delta (then
/// the join of light[s - 1] to the merged vertex is no strategy). The same sum as other_strategies
/// in another order, in time independent of the subpaths' lengths.
inline float merge_weight_from_factors(const JoinDensities& join, const MergeCameraFactors& camera,
                                       float light_factor, bool after_delta,
                                       const StrategyRules& rules) {
  const float camera_end = nonzero(join.camera_end);
  const float camera_before = nonzero(join.camera_before);
  const float light_end = nonzero(join.light_end);
  const float merge = rules.merge_density * camera_end;
  return merge * merge /
         ((after_delta ? 0.0f : 1.0f) +
          camera_end * camera_end * (camera.p + camera_before * camera_before * camera.q) +
          light_end * light_end * light_factor);
}

/// The reverse densities the vertices of light[0, s) and camera[0, t) hold themselves.
template <typename V>
JoinDensities held_densities(std::span<const V> light, std::span<const V> camera) {
  const auto reverse = [](std::span<const V> path, std::size_t from_end) {
    return path.size() > from_end ? path[path.size() - 1 - from_end].pdf_reverse : 0.0f;
  };
  return {reverse(light, 0), reverse(light, 1), reverse(camera, 0), reverse(camera, 1)};
}

}  // namespace detail

/// The power heuristic's weight of strategy (s, t) for the full path made of light[0, s) and
/// camera[0, t) (light[0] on a light, camera[0] the camera), whose vertices' pdf_forward and
/// pdf_reverse are the densities of both directions along this full path: the joined vertices'
/// reverse densities already set for the join (their deltas are read as cleared: their own next
/// vertices are not on this path). Exposed for tests, which hold it against an explicit sum over
/// all strategies.
template <typename V>
float bidirectional_weight(std::span<const V> light, std::span<const V> camera,
                           const StrategyRules& rules) {
  return detail::join_weight(light, camera, detail::held_densities(light, camera), rules);
}

/// The power heuristic's weight of merging at camera[t - 1] a light vertex that light[s - 1]
/// made (s >= 1, t >= 2): the full path is light[0, s), the merged vertex, camera[0, t - 1),
/// with the same densities as for bidirectional_weight, camera[t - 1]'s reverse density the one
/// with which light[s - 1] made the light vertex. Exposed for tests.
template <typename V>
float merge_weight(std::span<const V> light, std::span<const V> camera,
                   const StrategyRules& rules) {
  return detail::merge_weight(light, camera, detail::held_densities(light, camera), rules);
}

/// A light vertex at which camera vertices may merge, with everything a merge needs of its light
/// subpath (BidirectionalPathTracer::merge_candidates), so that merging reads nothing else.
struct MergeCandidate {
  Vec3 point;
  std::uint32_t sphere;
  Color beta;  ///< the light subpath's weight at the vertex
  /// Towards the vertex the light came from, in four bytes: the candidates of a pass are the
  /// largest thing a render holds.
  OctahedralDirection arrival;
  float pdf_forward;  ///< the density with which the light subpath made the vertex, per unit area
  /// The light side's share of the weight's denominator per squared density, per unit solid
  /// angle, with which the merging vertex's Bsdf chooses `arrival` (merge_light_factor, with the
  /// geometry of the edge to the vertex before).
  float light_factor;
  std::uint16_t vertex;  ///< its index on its subpath
  bool outward;          ///< the light arrived on the sphere's outer side
  bool after_delta;      ///< the vertex before went on through a delta
};
static_assert(sizeof(MergeCandidate) == 44);

/// A camera vertex merging, with what is the same for every candidate
/// (BidirectionalPathTracer::merge_target).
template <typename V>
struct MergeTarget {
  const V* vertex;
  Vec3 toward_camera;     ///< unit direction towards the camera subpath's vertex before
  float camera_geometry;  ///< per unit solid angle to per unit area at the vertex before
  detail::MergeCameraFactors factors;
  int camera_vertices;  ///< t: the vertex is the subpath's t-th
  bool outward;         ///< the camera subpath arrived on the sphere's outer side
  float merge_density;
};

/// Bidirectional path tracing with the policies of Config C: its sampler, material model and path
/// termination; each subpath samples the hit's Bsdf once per vertex in its own transport mode,
/// and joins and merges evaluate the vertices' Bsdf records.
template <RenderConfig C>
class BidirectionalPathTracer {
  static_assert(RecordableBsdf<BsdfAt<C>, typename C::sampler>);

 public:
  using SamplerType = typename C::sampler;
  using Vertex = PathVertexOf<C>;
  using Kind = PathVertexKind;

  /// `pixels`: the image's width x height, the light paths of one sample per pixel.
  /// `light_tracing_counts`: whether the pixel filter has an area, so that joins to the camera
  /// can land on pixels.
  BidirectionalPathTracer(const Scene& scene, const Camera& camera, int max_depth, float pixels,
                          bool light_tracing_counts)
      : scene_(scene),
        camera_(camera),
        lights_(scene),
        selection_(lights_),
        context_(scene, max_depth),
        most_vertices_(max_depth + 1),
        pixels_(pixels),
        light_tracing_counts_(light_tracing_counts) {}

  /// The most vertices a subpath holds (the camera or the light's point included): the size of
  /// the scratch spans that sample() takes.
  int subpath_capacity() const { return most_vertices_ + 2; }

  /// One sample: the camera subpath starts with `ray` through the film point whose density in
  /// its pixel's filter is `filter_density`, with values from `camera_sampler`; the light
  /// subpath draws from `light_sampler`. Returns the light for the pixel; joins to the camera
  /// go to `splat(film, light, filter_weight)`, where the light arriving at film point `film`
  /// counts, in a pixel whose filter density there is h, with the power heuristic's weight
  /// 1 / (1 + h^2 filter_weight) (filter_weight from bidirectional_weight's terms for h = 1).
  /// `camera_vertices` and `light_vertices` are scratch of subpath_capacity() vertices.
  template <typename Splat>
  Color sample(const Ray& ray, float filter_density, SamplerType& camera_sampler,
               SamplerType& light_sampler, std::span<Vertex> camera_vertices,
               std::span<Vertex> light_vertices, Splat&& splat, TraceCounters& counters) const {
    const std::size_t t_count =
        camera_subpath(ray, filter_density, camera_sampler, camera_vertices, counters);
    const std::size_t s_count = light_subpath(light_sampler, light_vertices, counters);
    return connect(camera_vertices.first(t_count), light_vertices.first(s_count), camera_sampler,
                   splat, 0.0f, counters);
  }

  /// Every join of camera subpath `z` (z[0] the camera) and light subpath `y` (y[0] on a light;
  /// may be empty): the light for the pixel, with joins to the camera going to `splat` as in
  /// sample(). `merge_density`: vertex merging's eta where merges compete for the same paths
  /// (merge()), zero for bidirectional path tracing alone.
  template <typename Splat>
  Color connect(std::span<const Vertex> z, std::span<const Vertex> y, SamplerType& camera_sampler,
                Splat&& splat, float merge_density, TraceCounters& counters) const {
    const StrategyRules rules{light_tracing_counts_, merge_density};
    Color radiance(0.0f);
    for (std::size_t t = 1; t <= z.size(); ++t)
      for (std::size_t s = 0; s <= y.size(); ++s) {
        // s + t - 2 scattering vertices; (0, 1) would be the camera alone. (1, 1) is a lamp
        // seen by the camera, joined to it as light tracing joins it.
        if (s + t < 2 || int(s + t) - 2 > most_vertices_) continue;
        if (s == 0) {
          if (t >= 2) radiance += emitted(z.first(t), rules);
        } else if (t == 1) {
          if (light_tracing_counts_)
            join_camera(y.first(s), rules, camera_sampler, splat, counters);
        } else if (s == 1) {
          radiance += join_light(z.first(t), rules, camera_sampler, counters);
        } else {
          radiance += join(y.first(s), z.first(t), rules, counters);
        }
      }
    return radiance;
  }

  /// Vertex merging (Georgiev et al. 2012; Hachisuka et al. 2012), on the light side: calls
  /// visit(candidate) for each vertex of light subpath `y` (after the light's own point) at which
  /// light may be merged, with what a merge needs of the subpath (MergeCandidate), for merges of
  /// density factor `merge_density` (Georgiev et al.'s eta). Sets the subpath's strategy tails.
  template <typename Visit>
  void merge_candidates(std::span<Vertex> y, float merge_density, Visit&& visit) const {
    const StrategyRules rules{light_tracing_counts_, merge_density};
    detail::strategy_tails(y, true, rules);
    for (std::size_t k = 1; k < y.size(); ++k) {
      const Vertex& photon = y[k];
      if (photon.kind != Kind::surface || !photon.joinable()) continue;
      const Vertex& from = y[k - 1];
      // Per unit solid angle at the merging point to per unit area at `from`, taken at the light
      // vertex (within the radius of the merging point).
      const float geometry = detail::area_density(1.0f, photon, from);
      if (!(geometry > 0.0f)) continue;
      const Vec3 arrival = towards(photon, from);
      const float light_factor = detail::merge_light_factor<Vertex>(y.first(k), rules);
      visit(MergeCandidate{photon.point, photon.sphere, photon.beta, OctahedralDirection(arrival),
                           photon.pdf_forward, geometry * geometry * light_factor, std::uint16_t(k),
                           glm::dot(photon.facing, photon.normal) > 0.0f, from.delta});
    }
  }

  /// Sets the strategy tails of camera subpath `z` for merges of density factor
  /// `merge_density`, before merge_target.
  void prepare_camera_merges(std::span<Vertex> z, float merge_density) const {
    detail::strategy_tails(z, false, StrategyRules{light_tracing_counts_, merge_density});
  }

  /// Vertex merging on the camera side: what merging at camera vertex z[t - 1] (t >= 2) needs of
  /// the camera subpath z (its strategy tails set by prepare_camera_merges), the same for every
  /// candidate; none where the vertex cannot merge (it is not on a surface, or its Bsdf has no
  /// density).
  std::optional<MergeTarget<Vertex>> merge_target(std::span<const Vertex> z,
                                                  float merge_density) const {
    const std::size_t t = z.size();
    const Vertex& pt = z[t - 1];
    if (pt.kind != Kind::surface || !pt.joinable()) return std::nullopt;
    const StrategyRules rules{light_tracing_counts_, merge_density};
    const Vertex& before = z[t - 2];
    const float geometry = detail::area_density(1.0f, pt, before);
    if (!(geometry > 0.0f)) return std::nullopt;
    const Vec3 toward_camera = towards(pt, before);
    return MergeTarget<Vertex>{&pt,          toward_camera,
                               geometry,     detail::merge_camera_factors<Vertex>(z, rules),
                               int(t),       glm::dot(pt.facing, pt.normal) > 0.0f,
                               merge_density};
  }

  /// The light that light vertex `candidate` carries to the camera vertex of `target` when it
  /// lies within the merging radius of it, for the pixel: its weight, over the light paths that
  /// could have brought it, with the uniform kernel over the radius's disc, 1 / merge_density in
  /// all. Zero where the path would be too long, where the light vertex lies on another sphere
  /// or on the other side of it (unless the camera vertex's Bsdf transmits with a density), or
  /// where that Bsdf does not take the light.
  Color merge(const MergeTarget<Vertex>& target, const MergeCandidate& candidate) const {
    const Vertex& pt = *target.vertex;
    if (int(candidate.vertex) + target.camera_vertices - 2 > most_vertices_ ||
        candidate.sphere != pt.sphere ||
        (candidate.outward != target.outward && !pt.scattering.transmits_with_density()))
      return Color(0.0f);
    const Vec3 arrival = candidate.arrival.direction();
    const Color value = pt.scattering.f(pt.facing, target.toward_camera, arrival);
    if (value == Color(0.0f)) return Color(0.0f);
    // The camera vertex's densities for the light's direction and for the camera side's.
    const float light_pdf = pt.scattering.pdf(pt.facing, target.toward_camera, arrival);
    if (!(light_pdf > 0.0f)) return Color(0.0f);
    const JoinDensities join{
        light_pdf, 0.0f, candidate.pdf_forward,
        pt.scattering.pdf(pt.facing, arrival, target.toward_camera) * target.camera_geometry};
    const float weight = detail::merge_weight_from_factors(
        join, target.factors, candidate.light_factor, candidate.after_delta,
        StrategyRules{light_tracing_counts_, target.merge_density});
    return pt.beta * value * candidate.beta * (weight / target.merge_density);
  }

  /// The camera subpath into `z`, z[0] the camera, ending on the environment where its last ray
  /// escapes and the background is not black. Returns the vertices made.
  std::size_t camera_subpath(const Ray& ray, float filter_density, SamplerType& sampler,
                             std::span<Vertex> z, TraceCounters& counters) const {
    Vertex& eye = z[0];
    eye = Vertex{};
    eye.kind = Kind::camera;
    eye.point = ray.origin;  // the camera's position, or the lens point the ray leaves
    eye.beta = Color(1.0f);
    // The density of the ray's direction, per unit solid angle, as a strategy that splats would
    // have to match it: the filter's density over the light paths per sample.
    const float direction_pdf =
        filter_density * camera_.solid_angle_density(ray.direction) / pixels_;
    return walk(ray, eye.beta, direction_pdf, sampler, z, 1, Transport::radiance, counters);
  }

  /// The light subpath into `y`, y[0] on a light. Returns the vertices made (none where the
  /// scene has no light with power).
  std::size_t light_subpath(SamplerType& sampler, std::span<Vertex> y,
                            TraceCounters& counters) const {
    if (selection_.empty()) return 0;
    const LightSelectionByPower::Choice choice = selection_.choose(sampler.next_1d());
    const Vec2 u_point = sampler.next_2d();
    const Vec2 u_direction = sampler.next_2d();
    return lights_.visit(choice.light, [&](const auto& light) {
      const EmittedRay emitted = light.sample_le(u_point, u_direction);
      Vertex& source = y[0];
      source = Vertex{};
      source.kind = light.kAtInfinity      ? Kind::environment
                    : light.kDeltaPosition ? Kind::delta_light
                                           : Kind::area_light;
      source.point = emitted.ray.origin;
      source.normal = emitted.normal;
      source.sphere = emitted.sphere;
      source.light = choice.light;
      // A light at infinity is a direction first, then a point of the disc: its vertex's
      // density is the direction's, and the next vertex's comes from the disc's (area_density).
      source.pdf_forward =
          choice.probability * (light.kAtInfinity ? emitted.direction_pdf : emitted.position_pdf);
      source.beta = emitted.origin_weight(choice.probability);
      const Color beta = emitted.ray_weight(choice.probability);
      if (!(max_component(beta) > 0.0f)) return std::size_t(1);
      if constexpr (std::remove_cvref_t<decltype(light)>::kAtInfinity) {
        // The light comes from infinitely far away: it reaches the disc's point only if nothing
        // lies beyond it (a floor the disc dips below, the walls of a closed room), which the
        // disc, holding the spheres but the walls, does not ensure by itself.
        Ray from_light;
        from_light.origin = emitted.ray.origin;
        from_light.direction = -emitted.ray.direction;
        ++counters.rays;
        if (scene_.occluded(from_light)) return std::size_t(1);
      }
      return walk(emitted.ray, beta,
                  light.kAtInfinity ? emitted.position_pdf : emitted.direction_pdf, sampler, y, 1,
                  Transport::importance, counters);
    });
  }

 private:
  /// Follows `ray` from vertex v[first - 1], carrying `beta`, its direction drawn with density
  /// `direction_pdf` per unit solid angle (zero: through a delta), adding vertices to `v` while
  /// the path length allows; a camera subpath whose ray escapes ends on the environment (where
  /// the background is not black). Returns the number of vertices.
  std::size_t walk(Ray ray, Color beta, float direction_pdf, SamplerType& sampler,
                   std::span<Vertex> v, std::size_t first, Transport mode,
                   TraceCounters& counters) const {
    const float start = max_component(beta);
    std::size_t n = first;
    for (;;) {
      const std::optional<SphereHit> hit = context_.closest_hit(ray, counters);
      if (!hit) {
        // The background is a light that other strategies reach too: the escape is a vertex on
        // it, strategy s = 0 (emitted). A black one brings nothing.
        if (mode != Transport::radiance) return n;
        if (const std::optional<LightId> environment = lights_.environment_light()) {
          Vertex& vertex = v[n];
          vertex = Vertex{};
          vertex.kind = Kind::environment;
          vertex.point = ray.origin + ray.direction;
          vertex.facing = ray.direction;
          vertex.light = *environment;
          vertex.beta = beta;
          vertex.pdf_forward = detail::area_density(direction_pdf, v[n - 1], vertex);
          return n + 1;
        }
        return n;
      }
      const SurfaceInteraction it = context_.interaction(ray, *hit);
      Vertex& vertex = v[n];
      Vertex& previous = v[n - 1];
      vertex = Vertex{};
      vertex.kind = Kind::surface;
      vertex.point = it.point;
      vertex.normal = it.outward_normal;
      vertex.facing = it.at.facing_normal;
      vertex.sphere = it.sphere;
      vertex.beta = beta;
      vertex.pdf_forward = detail::area_density(direction_pdf, previous, vertex);
      ++n;
      // The vertex's depth: scattering vertices before it on its subpath (the camera and the
      // light's point are not).
      const int depth = int(n) - 2;
      if (!context_.scatters_at(depth)) return n;
      const BsdfAt<C> bsdf(it, ray.direction);
      if (!bsdf.scatters()) return n;
      vertex.scattering = mode == Transport::radiance
                              ? bsdf.template record<Transport::radiance>()
                              : bsdf.template record<Transport::importance>();
      // A light subpath's vertex is joined to camera vertices and to the camera; it goes on only
      // where a longer path is allowed. A camera subpath goes on as the path tracer does.
      const bool goes_on = mode == Transport::radiance ? bool(context_.bounces_from(depth))
                                                       : depth < context_.max_depth();
      if (!goes_on || n == v.size()) return n;
      if constexpr (C::path_termination::uses_roulette) {
        const float p =
            C::path_termination::continue_probability(depth, max_component(beta) / start);
        if (p < 1.0f) {
          if (sampler.next_1d() >= p) return n;
          beta /= p;
        }
      }
      const ScatterSample next = mode == Transport::radiance
                                     ? bsdf.template sample<Transport::radiance>(sampler)
                                     : bsdf.template sample<Transport::importance>(sampler);
      beta *= next.weight();
      if (next.delta) {
        vertex.delta = true;
        direction_pdf = 0.0f;
      } else {
        direction_pdf = next.pdf;
        // The reverse density of the previous vertex: this one choosing it, from the next.
        previous.pdf_reverse = area_density_from(vertex, next.direction, previous);
      }
      if (!(max_component(beta) > 0.0f)) return n;
      ray = PathContext<C>::continue_rays(it, next.direction);
    }
  }

  /// The unit direction from vertex `v` to vertex `to`.
  static Vec3 towards(const Vertex& v, const Vertex& to) {
    return glm::normalize(to.point - v.point);
  }

  /// Density per unit area with which surface vertex `v`, reached from unit direction `arrival`,
  /// scatters its path to `to` (its Bsdf record's density).
  static float area_density_from(const Vertex& v, const Vec3& arrival, const Vertex& to) {
    return detail::area_density(v.scattering.pdf(v.facing, arrival, towards(v, to)), v, to);
  }

  /// Density per unit area with which light vertex `v` emits towards `to`: for the
  /// environment, that of the light path through its disc that reaches `to` (zero where none
  /// does), times the cosine at `to`.
  float emission_density(const Vertex& v, const Vertex& to) const {
    const float pdf = lights_.visit(v.light, [&](const auto& light) {
      if constexpr (std::remove_cvref_t<decltype(light)>::kAtInfinity)
        return light.disc_density(towards(to, v), to.point);
      else
        return light.pdf_le(v.normal, towards(v, to)).direction;
    });
    return detail::area_density(pdf, v, to);
  }

  /// Whether nothing lies between surface vertex a and vertex b (on a sphere, or a point
  /// light's point).
  bool visible(const Vertex& a, const Vertex& b, TraceCounters& counters) const {
    const Vec3 offset = b.point - a.point;
    const float distance = std::sqrt(glm::dot(offset, offset));
    if (!(distance > 0.0f)) return false;
    const Vec3 direction = offset / distance;
    const Ray ray = ray_leaving_sphere(a.point, direction, a.sphere, a.normal);
    ++counters.rays;
    if (b.sphere == kNoSphere) {
      Ray shadow = ray;
      shadow.t_max = distance;
      return !scene_.occluded(shadow);
    }
    // The ray reaches b where the first sphere it meets is b's, met on b's side: entering it
    // where b faces the ray, from inside where b faces away. No distance decides it, so no
    // rounding of one does.
    const std::optional<SphereHit> hit = scene_.closest_hit(ray);
    if (!hit || hit->sphere != b.sphere) return false;
    const Vec3 at = ray.origin + hit->t * ray.direction;
    const bool enters_hit = glm::dot(ray.direction, at - scene_.surface(b.sphere).center) < 0.0f;
    return enters_hit == (glm::dot(direction, b.normal) < 0.0f);
  }

  /// Strategy s = 0: the camera subpath's last vertex on an emissive sphere or on the
  /// environment.
  Color emitted(std::span<const Vertex> z, const StrategyRules& rules) const {
    const std::size_t t = z.size();
    const Vertex& pt = z[t - 1];
    if (pt.kind == Kind::environment) {
      // As a light's vertex: the density of its direction, chosen as light subpaths choose it,
      // and the disc's towards z[t - 2].
      const Environment::Found found = scene_.environment().find(pt.facing);
      const float from_disc = emission_density(pt, z[t - 2]);
      const float weight =
          detail::join_weight({}, z,
                              {0.0f, 0.0f, selection_.probability(pt.light) * found.pdf, from_disc,
                               false, !(from_disc > 0.0f)},
                              rules);
      return pt.beta * found.radiance * weight;
    }
    const std::uint32_t emitter = scene_.surface(pt.sphere).emitter;
    if (emitter == kNotAnEmitter) return Color(0.0f);
    const Color le = scene_.surface(pt.sphere).material.emission;
    // As a light's vertex: its origin density, and its emission towards z[t - 2].
    const Vertex light_view = as_light(pt, emitter);
    const float weight = detail::join_weight(
        {}, z, {0.0f, 0.0f, light_view.pdf_forward, emission_density(light_view, z[t - 2])}, rules);
    return pt.beta * le * weight;
  }

  /// Surface vertex `v` on emitter `emitter` seen as the first vertex of a light subpath.
  Vertex as_light(const Vertex& v, std::uint32_t emitter) const {
    Vertex light = v;
    light.kind = Kind::area_light;
    light.light = lights_.sphere_light(emitter);
    light.pdf_forward =
        selection_.probability(light.light) * lights_.visit(light.light, [&](const auto& l) {
          return l.pdf_le(v.normal, v.normal).position;
        });
    return light;
  }

  /// Strategy t = 1: light vertex y[s - 1] joined to the camera (through a lens point drawn
  /// from `sampler`, where the camera has a lens).
  template <typename Splat>
  void join_camera(std::span<const Vertex> y, const StrategyRules& rules, SamplerType& sampler,
                   Splat& splat, TraceCounters& counters) const {
    const std::size_t s = y.size();
    const Vertex& qs = y[s - 1];
    // The draw comes before the test of the vertex, so that every vertex draws the same.
    const std::optional<CameraConnection> to_camera = camera_.connect(qs.point, sampler);
    if (!qs.joinable() || !to_camera) return;
    Color value;
    if (qs.kind == Kind::area_light)
      value = qs.beta * std::fabs(glm::dot(to_camera->direction, qs.normal));
    else if (qs.kind == Kind::surface)
      value = qs.beta * qs.scattering.f(qs.facing, towards(qs, y[s - 2]), to_camera->direction) *
              std::fabs(glm::dot(to_camera->direction, qs.normal));
    else
      return;  // a point light: the camera cannot see a point
    if (value == Color(0.0f)) return;
    ++counters.rays;
    if (scene_.occluded(ray_leaving_sphere(qs.point, to_camera->direction, qs.sphere, qs.normal,
                                           to_camera->unclipped_distance)))
      return;
    // The weight's terms for a filter density of one at the film point: the camera's density
    // for qs is h x solid_angle_density x |cos at qs| / distance^2 / pixels.
    Vertex eye{};
    eye.kind = Kind::camera;
    eye.point = to_camera->lens_point;
    const float camera_pdf =
        detail::area_density(camera_.solid_angle_density(-to_camera->direction) / pixels_, eye, qs);
    // 1 / w - 1 with the camera's density at h = 1: every term holds h^2 once.
    const float w = detail::join_weight(
        y, std::span<const Vertex>(&eye, 1),
        {camera_pdf, s >= 2 ? area_density_from(qs, to_camera->direction, y[s - 2]) : 0.0f, 0.0f,
         0.0f},
        rules);
    const float filter_weight = 1.0f / w - 1.0f;
    splat(to_camera->film, value * to_camera->importance, filter_weight);
  }

  /// Strategy s = 1: camera vertex z[t - 1] joined to a point drawn on a light: a light
  /// chosen by power (as light subpaths choose it), then the point light itself, or a direction
  /// towards the emissive sphere as the path tracer draws it (uniform in the cone it subtends,
  /// or through a uniform point of its area from inside). The weight counts the light's point
  /// with the light subpaths' density, as pbrt-v4 does, so that all strategies' weights come from
  /// one set of densities and sum to one.
  Color join_light(std::span<const Vertex> z, const StrategyRules& rules, SamplerType& sampler,
                   TraceCounters& counters) const {
    const std::size_t t = z.size();
    const Vertex& pt = z[t - 1];
    if (selection_.empty()) return Color(0.0f);
    // The draws come before the test of the vertex, so that every vertex draws the same.
    const LightSelectionByPower::Choice choice = selection_.choose(sampler.next_1d());
    const Vec2 u_point = sampler.next_2d();
    if (pt.kind != Kind::surface || !pt.joinable()) return Color(0.0f);
    const Vec3 to_camera_side = towards(pt, z[t - 2]);
    // A vertex that transmits with a density sees its own sphere's light from inside, whichever
    // side it was reached from.
    const bool from_inside =
        glm::dot(pt.facing, pt.normal) < 0.0f || pt.scattering.transmits_with_density();
    Vertex light{};
    const Color value = lights_.visit(choice.light, [&](const auto& source) {
      const LightSample sample =
          source.sample_li(LightPoint{pt.point, pt.sphere, from_inside}, u_point);
      if (!sample.valid || !(sample.pdf > 0.0f)) return Color(0.0f);
      const Color arriving =
          pt.beta * pt.scattering.f(pt.facing, to_camera_side, sample.direction) *
          (std::fabs(glm::dot(sample.direction, pt.normal)) / (choice.probability * sample.pdf)) *
          sample.radiance;
      if (arriving == Color(0.0f)) return Color(0.0f);
      light.kind = source.kDeltaPosition ? Kind::delta_light : Kind::area_light;
      light.light = choice.light;
      ++counters.rays;
      const Ray ray =
          ray_leaving_sphere(pt.point, sample.direction, pt.sphere, pt.normal, sample.distance);
      if constexpr (std::remove_cvref_t<decltype(source)>::kAtInfinity) {
        // The light arrives where the ray escapes; its vertex stands for the direction, with
        // the density light subpaths give it (as emitted() counts it).
        if (scene_.occluded(ray)) return Color(0.0f);
        light.kind = Kind::environment;
        light.point = pt.point + sample.direction;
        light.facing = sample.direction;
        light.pdf_forward = choice.probability * source.environment().pdf(sample.direction);
        return arriving;
      }
      if (sample.sphere == kNoSphere) {
        if (scene_.occluded(ray)) return Color(0.0f);
        light.point = sample.point;
      } else {
        // The light arrives where the first sphere along the direction is the light's.
        const std::optional<SphereHit> hit = scene_.closest_hit(ray);
        if (!hit || hit->sphere != sample.sphere) return Color(0.0f);
        light.point = ray.at(hit->t);
        light.sphere = sample.sphere;
      }
      light.normal = source.surface_normal(light.point);
      light.pdf_forward =
          choice.probability * source.pdf_le(light.normal, -sample.direction).position;
      return arriving;
    });
    if (value == Color(0.0f)) return Color(0.0f);
    // The light's density for pt; zero where no light path from the environment reaches it.
    const float to_vertex = emission_density(light, pt);
    const float weight =
        detail::join_weight(std::span<const Vertex>(&light, 1), z,
                            {area_density_from(pt, to_camera_side, light), 0.0f, to_vertex,
                             area_density_from(pt, towards(pt, light), z[t - 2]),
                             light.kind == Kind::environment && !(to_vertex > 0.0f)},
                            rules);
    return value * weight;
  }

  /// Strategies s, t >= 2: light vertex y[s - 1] joined to camera vertex z[t - 1].
  Color join(std::span<const Vertex> y, std::span<const Vertex> z, const StrategyRules& rules,
             TraceCounters& counters) const {
    const std::size_t s = y.size(), t = z.size();
    const Vertex& qs = y[s - 1];
    const Vertex& pt = z[t - 1];
    if (qs.kind != Kind::surface || pt.kind != Kind::surface || !qs.joinable() || !pt.joinable())
      return Color(0.0f);
    const Vec3 offset = pt.point - qs.point;
    const float distance2 = glm::dot(offset, offset);
    if (!(distance2 > 0.0f)) return Color(0.0f);
    const Vec3 direction = offset / std::sqrt(distance2);  // from qs to pt
    const float geometry = std::fabs(glm::dot(direction, qs.normal)) *
                           std::fabs(glm::dot(direction, pt.normal)) / distance2;
    const Vec3 to_light_side = towards(qs, y[s - 2]), to_camera_side = towards(pt, z[t - 2]);
    const Color value = qs.beta * qs.scattering.f(qs.facing, to_light_side, direction) * geometry *
                        pt.scattering.f(pt.facing, to_camera_side, -direction) * pt.beta;
    if (value == Color(0.0f) || !visible(qs, pt, counters)) return Color(0.0f);
    const float weight = detail::join_weight(
        y, z,
        {area_density_from(pt, to_camera_side, qs), area_density_from(qs, direction, y[s - 2]),
         area_density_from(qs, to_light_side, pt), area_density_from(pt, -direction, z[t - 2])},
        rules);
    return value * weight;
  }

  const Scene& scene_;
  const Camera& camera_;
  SceneLights lights_;
  LightSelectionByPower selection_;
  PathContext<C> context_;
  int most_vertices_;  ///< scattering vertices a path may have: max_depth + 1
  float pixels_;
  bool light_tracing_counts_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
