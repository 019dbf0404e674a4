// What the shading models' CPU tests share (tests/test_shading_models.cpp and each model's
// techniques/<folder>/test_*.cpp): a tangent, a strand colour and directions around it.
#pragma once

#include <cmath>
#include <glm/glm.hpp>

namespace sbtest {

inline constexpr float kPi = 3.14159265358979f;
inline const glm::vec3 kTangent{0, 1, 0};
inline const glm::vec3 kBrown{0.55f, 0.35f, 0.2f};

// A direction at longitudinal angle theta (to the normal plane, towards the tip) and azimuth
// phi, about kTangent.
inline glm::vec3 dir(float theta, float phi) {
  return {std::cos(theta) * std::cos(phi), std::sin(theta), std::cos(theta) * std::sin(phi)};
}

}  // namespace sbtest
