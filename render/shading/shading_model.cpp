#include "render/shading/shading_model.h"

namespace sb {

ShadingLobes ShadingLobes::from(const LobeOptions& o) {
  const float alpha = o.alpha * kDegree;
  const float beta = o.beta * kDegree;
  ShadingLobes l;
  // The paper's relations between the lobes (Marschner et al. 2003, Table 1; kept by Sadeghi).
  l.alpha = {alpha, -alpha / 2.0f, -3.0f * alpha / 2.0f, 0.0f};
  l.beta = {beta, beta / 2.0f, 2.0f * beta, 0.0f};
  l.diffuse = o.diffuse;
  l.specular = o.specular;
  return l;
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
