// Camera and light, fitted to a scene's bounds by default; every value can be
// overridden from the command line. Matrices use GLM with depth in [0,1]
// (GLM_FORCE_DEPTH_ZERO_TO_ONE) and no y-flip: one projection serves GL and Vulkan.
#pragma once

#include <glm/glm.hpp>

#include "scenes/scene.h"

namespace sb {

struct Camera {
  glm::vec3 eye{0, 0, 5};
  glm::vec3 target{0, 0, 0};
  glm::vec3 up{0, 1, 0};
  float fovYDegrees = 35.0f;
  float nearPlane = 0.1f;
  float farPlane = 100.0f;
  glm::mat4 view() const;
  glm::mat4 projection(float aspect) const;
};

enum class LightType { Directional, Point };

struct Light {
  LightType type = LightType::Directional;
  glm::vec3 position{5, 5, 5};      // point light position; for directional, a point on the
                                    // light side used to place the orthographic frustum
  glm::vec3 direction{-1, -1, -1};  // directional: direction light travels (normalized)
  glm::vec3 color{1, 1, 1};
  float intensity = 1.0f;
  // Light frustum fitted to the scene: orthographic (directional) or a
  // perspective cone that encloses the bounds (point).
  glm::mat4 view() const;
  glm::mat4 projection() const;
  float nearPlane = 0.1f, farPlane = 100.0f;
  float orthoHalfExtent = 1.0f;  // directional
  float fovYDegrees = 60.0f;     // point
};

// Near/far planes that enclose the bounds from the camera's eye.
void fitCameraPlanes(Camera& cam, const Bounds& b);
// Near/far, orthographic extent and cone angle that enclose the bounds from
// the light's position and direction.
void fitLightFrustum(Light& light, const Bounds& b);
// Front view at a distance that frames the bounds with a small margin.
// byBox: fit the bounding box seen from +z instead of the bounding sphere (Scene::frameByBox).
Camera fitCamera(const Bounds& b, float aspect, bool byBox = false);
// Key light from above-front-left; near/far and extent enclose the bounds.
Light fitLight(const Bounds& b, LightType type);

}  // namespace sb
