#pragma once
// A scene's lights, one list per kind (render/light.hpp). An estimator names a light by its
// LightId, its place in the lights of every kind taken in the order of SceneLightKinds, and reaches
// it through visit(), which calls a generic callable with the light's own type: no virtual call,
// and no estimator names a kind.
//
// The background is among them, an image or a colour that is not black (EnvironmentLight, last):
// bidirectional path tracing and vertex merging join to it and start light paths from it. Light
// tracing, whose light paths can never reach the camera from infinitely far away, needs a black
// background (light_paths_carry_all_light).
//
// To add a kind of light: a type that satisfies Light, a list of it in SceneLights's
// constructor, and its place in SceneLightKinds.

#include <cstddef>
#include <cstdint>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "glint/instruction_set.hpp"
#include "glint/render/light.hpp"
#include "glint/render/lights/environment_light.hpp"
#include "glint/render/lights/point_light_source.hpp"
#include "glint/render/lights/sphere_light.hpp"
#include "glint/scene/emitters.hpp"
#include "glint/scene/scene.hpp"

namespace glint::inline GLINT_ISA_NAMESPACE {

/// The kinds of light a scene holds, in the order of their LightIds.
template <Light... Kinds>
struct LightKinds {
  using Lists = std::tuple<std::vector<Kinds>...>;
};
using SceneLightKinds = LightKinds<PointLightSource, SphereLight, EnvironmentLight>;

/// A light of a scene: its place in the lists of every kind, taken in order.
using LightId = std::uint32_t;

/// Whether light paths carry all of a scene's light: its background, which starts none, is
/// black.
inline bool light_paths_carry_all_light(const Scene& scene) {
  return scene.environment().is_black();
}

class SceneLights {
 public:
  explicit SceneLights(const Scene& scene) {
    auto& points = std::get<std::vector<PointLightSource>>(lists_);
    for (const PointLight& light : scene.lights())
      points.emplace_back(light);
    auto& spheres = std::get<std::vector<SphereLight>>(lists_);
    for (const SphereEmitter& emitter : scene.emitters().emitters())
      spheres.emplace_back(emitter);
    if (!scene.environment().is_black())
      std::get<std::vector<EnvironmentLight>>(lists_).emplace_back(scene);
  }

  /// The number of lights of every kind.
  std::size_t size() const {
    return std::apply([](const auto&... list) { return (list.size() + ... + 0); }, lists_);
  }

  /// The light of emissive sphere `emitter` (its index in the scene's emitters).
  LightId sphere_light(std::uint32_t emitter) const {
    return LightId(std::get<std::vector<PointLightSource>>(lists_).size() + emitter);
  }

  /// The environment's light, if the scene's background is not black.
  std::optional<LightId> environment_light() const {
    if (std::get<std::vector<EnvironmentLight>>(lists_).empty()) return std::nullopt;
    return LightId(size() - 1);
  }

  /// Calls f(light) with light `id` as its own type, and returns what f returns (the same type
  /// for every kind). Requires id < size().
  template <typename Function>
  decltype(auto) visit(LightId id, Function&& f) const {
    return visit_from<0>(id, f);
  }

  /// Calls f(light) for every light, in the order of their ids.
  template <typename Function>
  void for_each(Function&& f) const {
    std::apply([&](const auto&... list) { (for_each_in(list, f), ...); }, lists_);
  }

 private:
  template <std::size_t Kind, typename Function>
  decltype(auto) visit_from(std::size_t id, Function& f) const {
    const auto& list = std::get<Kind>(lists_);
    if constexpr (Kind + 1 == std::tuple_size_v<SceneLightKinds::Lists>) {
      return f(list[id]);
    } else {
      if (id < list.size()) return f(list[id]);
      return visit_from<Kind + 1>(id - list.size(), f);
    }
  }

  template <typename List, typename Function>
  static void for_each_in(const List& list, Function& f) {
    for (const auto& light : list)
      f(light);
  }

  SceneLightKinds::Lists lists_;
};

}  // namespace glint::inline GLINT_ISA_NAMESPACE
