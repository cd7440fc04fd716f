#pragma once
// A small scene for the renderer's mechanics (passes, progress): a diffuse ball, a glass ball
// beside it and a point light, so that every pixel's samples take a few rays of either kind.

#include <string>

#include "glint/scene/scene.hpp"

namespace glint::test {

inline Scene small_scene(const std::string& source) {
  SceneDescription d;
  d.source = source;
  d.camera.position = {0.0f, 0.0f, 10.0f};
  SphereDescription sphere;
  sphere.radius = 3.0f;
  d.spheres.push_back(sphere);
  SphereDescription glass;
  glass.center = {2.0f, 1.0f, 3.0f};
  glass.material.diffuse = 0.0f;
  glass.material.transparent = 1.0f;
  d.spheres.push_back(glass);
  d.lights.push_back({{5.0f, 5.0f, 10.0f}, 100.0f, Color(1.0f), 1});
  return Scene::build(d);
}

}  // namespace glint::test
