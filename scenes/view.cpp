// Camera and light matrices and their default fit to a scene's bounds.
#include "scenes/view.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace sb {

namespace {

// An up vector that is not parallel to the viewing direction.
glm::vec3 safeUp(const glm::vec3& dir, const glm::vec3& up) {
  const float len = glm::length(dir);
  if (!(len > 0.0f)) return up;
  const glm::vec3 d = dir / len;
  if (std::abs(glm::dot(d, glm::normalize(up))) < 0.99f) return up;
  return std::abs(d.y) < 0.9f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
}

// Radius of the bounds, never zero (a single point still gets a usable frustum).
float safeRadius(const Bounds& b) {
  const float r = b.radius();
  const float scale =
      std::max({1e-3f, std::abs(b.center().x), std::abs(b.center().y), std::abs(b.center().z)});
  return std::isfinite(r) ? std::max(r, 1e-4f * scale) : 1.0f;
}

}  // namespace

glm::mat4 Camera::view() const { return glm::lookAt(eye, target, safeUp(target - eye, up)); }

glm::mat4 Camera::projection(float aspect) const {
  return glm::perspective(glm::radians(fovYDegrees), aspect, nearPlane, farPlane);
}

glm::mat4 Light::view() const {
  return glm::lookAt(position, position + direction, safeUp(direction, glm::vec3(0, 1, 0)));
}

glm::mat4 Light::projection() const {
  if (type == LightType::Directional) {
    return glm::ortho(-orthoHalfExtent, orthoHalfExtent, -orthoHalfExtent, orthoHalfExtent,
                      nearPlane, farPlane);
  }
  return glm::perspective(glm::radians(fovYDegrees), 1.0f, nearPlane, farPlane);
}

void fitCameraPlanes(Camera& cam, const Bounds& b) {
  const float r = safeRadius(b);
  const float dist = glm::length(b.center() - cam.eye);
  cam.nearPlane = std::max(dist - 1.02f * r, 1e-3f * (dist + r));
  cam.farPlane = dist + 1.02f * r;
}

Camera fitCamera(const Bounds& b, float aspect, bool byBox) {
  Camera cam;
  const glm::vec3 c = b.center();
  const float r = safeRadius(b);
  const float halfY = 0.5f * glm::radians(cam.fovYDegrees);
  const float a = aspect > 0.0f && std::isfinite(aspect) ? aspect : 1.0f;
  const float halfX = std::atan(std::tan(halfY) * a);
  const float half = std::min(halfY, halfX);
  const float margin = 1.08f;
  float dist = margin * r / std::sin(half);
  if (byBox) {
    // The box's front face (nearest the camera, the largest in the image) just inside
    // the frame: an elongated model fills the frame along its long side.
    const glm::vec3 h = glm::max(0.5f * (b.max - b.min), glm::vec3(1e-4f * r));
    const float fit = std::max(h.x / std::tan(halfX), h.y / std::tan(halfY));
    if (std::isfinite(fit)) dist = h.z + 1.04f * fit;
  }
  cam.target = c;
  cam.eye = c + glm::vec3(0.0f, 0.0f, dist);  // looks along -z
  cam.up = glm::vec3(0, 1, 0);
  fitCameraPlanes(cam, b);
  return cam;
}

void fitLightFrustum(Light& light, const Bounds& b) {
  const float r = safeRadius(b);
  const float pad = 1.01f;  // a little slack so the sphere's extremes are not clipped
  const float dist = glm::dot(b.center() - light.position, light.direction);
  light.nearPlane = std::max(dist - pad * r, 1e-4f * (std::abs(dist) + r));
  light.farPlane = std::max(dist + pad * r, 1.001f * light.nearPlane);
  light.orthoHalfExtent = pad * r;
  // Point light: half-angle of the cone tangent to the sphere, padded.
  const float toCenter = glm::length(b.center() - light.position);
  light.fovYDegrees =
      toCenter > pad * r ? glm::degrees(2.0f * std::asin(pad * r / toCenter)) : 170.0f;
}

Light fitLight(const Bounds& b, LightType type) {
  Light light;
  light.type = type;
  // Travels down, back and to -x: from above and in front of the scene.
  light.direction = glm::normalize(glm::vec3(-1.0f, -1.2f, -0.8f));
  // Outside the bounding sphere; a point light further, for a narrower cone.
  const float dist = (type == LightType::Directional ? 2.0f : 3.0f) * safeRadius(b);
  light.position = b.center() - light.direction * dist;
  fitLightFrustum(light, b);
  return light;
}

}  // namespace sb
