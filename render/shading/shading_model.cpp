#include "render/shading/shading_model.h"

#include <algorithm>
#include <cmath>

#include "base/options.h"

namespace sb {

namespace {

// The shaders bound cos^2(theta_d) below by this (marschner.glsl, sadeghi.glsl).
constexpr float kMinCos2 = 1e-2f;

}  // namespace

ShadingModel ShadingModel::withLobes(const Lobes& l) {
  const float alpha = l.alpha * kDegree;
  const float beta = l.beta * kDegree;
  ShadingModel m;
  m.shift = {alpha, -alpha / 2.0f, -3.0f * alpha / 2.0f, 0.0f};
  m.width = {beta, beta / 2.0f, 2.0f * beta, 0.0f};
  m.material = {l.diffuse, l.specular, 0.0f, 0.12f};
  return m;
}

float ShadingModel::maxSpecular() const {
  switch (kind) {
    case ShadingKind::KajiyaKay:
      return 1.0f;
    case ShadingKind::Marschner: {
      // Per lobe: the Gaussian's peak 1/(beta sqrt(2 pi)) times N's bound: at most 3 roots,
      // each with attenuation <= 1 over |2 dphi/dh| >= max(4 (R), 2 caustic).
      float s = 0.0f;
      for (int p = 0; p < 3; ++p) {
        const float peak = 1.0f / (width[p] * 2.50662827463f);
        const float n = p == 0 ? 1.0f / 4.0f : 3.0f / (2.0f * width.w);
        s += peak * n;
      }
      return s / kMinCos2;
    }
    case ShadingKind::Sadeghi:
      return (intensity.x + intensity.y + intensity.z * (1.0f + intensity.w)) / kMinCos2;
    case ShadingKind::Chiang:
      return specularBound;
  }
  return 1.0f;
}

float ShadingModel::shadowAlpha(const Scene& scene) const {
  if (!fibreShadowAlpha) return scene.shadowAlpha;
  const std::vector<glm::vec3>& colors = scene.strands.colors;
  glm::dvec3 sum(0.0);
  for (const glm::vec3& c : colors) sum += glm::dvec3(c);
  const glm::vec3 mean = colors.empty() ? scene.hairColor : glm::vec3(sum / double(colors.size()));
  return fibreShadowAlpha(mean);
}

}  // namespace sb
