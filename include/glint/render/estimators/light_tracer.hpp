#pragma once
// Light tracing: paths followed from the lights, each vertex connected to the camera. It finds
// the light that camera paths cannot: a point light's light focused by glass onto a diffuse
// surface (a caustic), which a camera path can reach only through a shadow ray that the glass
// blocks. It cannot find what the camera sees through a mirror or glass, or a point light's
// direct view (a connection to the camera needs a surface that scatters in every direction), so
// on its own it estimates the light of the paths whose first vertex from the camera is diffuse
// or on a light; the bidirectional estimators combine it with camera paths.
//
// A path's contributions are splats: each lands where the camera sees its vertex, on whichever
// pixels' filters cover that point. The same Config as the camera paths: its sampler, material
// model and path termination; the hit's Bsdf sampled once per vertex in the importance transport
// mode, and every vertex where it has a density connected to the camera.
//
// Path length is counted as the camera paths count it (render/estimators/path_context.hpp), so
// that both estimate the same image for the same max_depth: the light of every light after at
// most max_depth + 1 scattering vertices between it and the camera.

#include <cmath>
#include <optional>

#include "glint/config.hpp"
#include "glint/geometry/ray.hpp"
#include "glint/instruction_set.hpp"
#include "glint/render/bsdf.hpp"
#include "glint/render/camera.hpp"
#include "glint/render/estimators/path_context.hpp"
#include "glint/render/light_selection.hpp"
#include "glint/render/materials.hpp"
#include "glint/render/scattering.hpp"
#include "glint/render/scene_lights.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// Follows light paths with the policies of Config C and hands each connection to the camera to
/// a splat callback.
template <RenderConfig C>
class LightTracer {
  static_assert(Bsdf<BsdfAt<C>, float, typename C::sampler>);

 public:
  using SamplerType = typename C::sampler;

  LightTracer(const Scene& scene, const Camera& camera, int max_depth)
      : scene_(scene),
        camera_(camera),
        lights_(scene),
        selection_(lights_),
        max_depth_(max_depth) {}

  const LightSelectionByPower& selection() const { return selection_; }

  /// Follows one light path with values from `sampler` (started by the caller) and calls
  /// `splat(film, value)` for each of its connections to the camera: `value` is the light the
  /// connection brings, per unit of the pixel filter's density at `film` minus a pixel's centre.
  /// Draws, in order: the light (1d), the point on it (2d), the direction (2d); then at each
  /// vertex roulette where C::path_termination plays (1d) and the direction (as the Bsdf's
  /// sample draws); with a lens, each connection to the camera first draws its lens point (2d).
  template <typename Splat>
  void trace(SamplerType& sampler, Splat&& splat, TraceCounters& counters) const {
    if (selection_.empty()) return;
    const LightSelectionByPower::Choice choice = selection_.choose(sampler.next_1d());
    const Vec2 u_point = sampler.next_2d();
    const EmittedRay emitted = lights_.visit(choice.light, [&](const auto& light) {
      return light.sample_le(u_point, sampler.next_2d());
    });
    // The vertices a path may have between the light and the camera (see above).
    const int most_vertices = max_depth_ + 1;
    // The light's emission at its point over the densities of the light and the point.
    const Color at_light = emitted.origin_weight(choice.probability);

    // A light with a surface seen by the camera: its radiance from the point, on both sides.
    if (emitted.sphere != kNoSphere)
      connect(
          emitted.ray.origin, emitted.sphere, emitted.normal,
          [&](const Vec3& to_camera) {
            return at_light * std::fabs(glm::dot(to_camera, emitted.normal));
          },
          sampler, splat, counters);

    Ray ray = emitted.ray;
    Color weight = emitted.ray_weight(choice.probability);
    const float start = max_component(weight);
    if (!(start > 0.0f)) return;
    for (int vertex = 1; vertex <= most_vertices; ++vertex) {
      ++counters.rays;
      const std::optional<SphereHit> hit = scene_.closest_hit(ray);
      if (!hit) return;
      const SurfaceInteraction it =
          SurfaceInteraction::at_hit(scene_, ray.origin, ray.direction, hit->t, hit->sphere, true);
      const BsdfAt<C> bsdf(it, ray.direction);
      if (bsdf.has_density())
        connect(
            it.point, it.sphere, it.outward_normal,
            // f cos at the vertex: zero where the camera is on the other side of the surface.
            [&](const Vec3& to_camera) {
              return weight * bsdf.template evaluate<Transport::importance>(to_camera);
            },
            sampler, splat, counters);
      if (vertex == most_vertices || !bsdf.scatters()) return;
      // Roulette on the weight relative to the light's, which is what a camera path's
      // throughput of one means here.
      if constexpr (C::path_termination::uses_roulette) {
        const float p =
            C::path_termination::continue_probability(vertex - 1, max_component(weight) / start);
        if (p < 1.0f) {
          if (sampler.next_1d() >= p) return;
          weight /= p;
        }
      }
      const ScatterSample next = bsdf.template sample<Transport::importance>(sampler);
      weight *= next.weight();
      ray = PathContext<C>::continue_rays(it, next.direction);
    }
  }

 private:
  /// Connects `point`, on sphere `sphere` of outward normal `normal` there, to the camera:
  /// where the camera sees it and nothing blocks the way, splats light(direction to the camera)
  /// times the camera's importance. A connection that brings nothing traces no ray.
  template <typename Light, typename Splat>
  void connect(const Vec3& point, std::uint32_t sphere, const Vec3& normal, Light&& light,
               SamplerType& sampler, Splat& splat, TraceCounters& counters) const {
    const std::optional<CameraConnection> to_camera = camera_.connect(point, sampler);
    if (!to_camera) return;
    const Color value = light(to_camera->direction);
    if (value == Color(0.0f)) return;
    ++counters.rays;
    if (scene_.occluded(ray_leaving_sphere(point, to_camera->direction, sphere, normal,
                                           to_camera->unclipped_distance)))
      return;
    splat(to_camera->film, value * to_camera->importance);
  }

  const Scene& scene_;
  const Camera& camera_;
  SceneLights lights_;
  LightSelectionByPower selection_;
  int max_depth_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
