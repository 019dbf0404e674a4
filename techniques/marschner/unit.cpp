// --shading marschner.
#include "render/common/unit.h"

#include <algorithm>
#include <cmath>

#include "techniques/marschner/marschner.h"

namespace sb {
namespace {
struct O {
  LobeOptions lobes;
  float eta, caustic, ambient;
};
const OptionTable<O> kOptions(
    {opt::lobes(&O::lobes, "weight of a Kajiya-Kay diffuse term (the thesis adds one), 0..4",
                "weight of the scattering function, 0..4"),
     opt::number(&O::eta, "eta", "1.55", 1.01, 3, "index of refraction of the fibre, 1.01..3"),
     opt::number(&O::caustic, "caustic", "0.5", 0.01, 4,
                 "floor on |dphi/dh| bounding the TRT caustic (the paper fades it with a "
                 "Gaussian), 0.01..4"),
     opt::number(&O::ambient, "ambient", "0.12", 0, 1,
                 "ambient term, a fraction of the hair colour (0: none, as the path-traced "
                 "reference has), 0..1")});

// The scattering function's largest value: per lobe, the Gaussian's peak 1/(beta sqrt(2 pi))
// times N's bound (at most 3 roots, each with attenuation <= 1 over |2 dphi/dh| >= max(4 (R),
// 2 caustic)), over the shader's bound on cos^2(theta_d).
float maxScattering(const MarschnerParams& p) {
  float s = 0.0f;
  for (int l = 0; l < 3; ++l) {
    const float peak = 1.0f / (p.marschnerBeta[l] * 2.50662827463f);
    const float n = l == 0 ? 1.0f / 4.0f : 3.0f / (2.0f * p.marschnerCaustic);
    s += peak * n;
  }
  return s / kMinCos2;
}
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShading = [](const OptionReader& r) {
                const O o = kOptions.read(r);
                const ShadingLobes lobes = ShadingLobes::from(o.lobes);
                MarschnerParams p{};
                p.marschnerAlpha = lobes.alpha;
                p.marschnerBeta = lobes.beta;
                p.marschnerDiffuse = lobes.diffuse;
                p.marschnerSpecular = lobes.specular;
                p.marschnerEta = o.eta;
                p.marschnerCaustic = o.caustic;
                ShadingModel m;
                m.setParams(p);
                m.ambient = o.ambient;
                m.maxDirect = p.marschnerDiffuse + p.marschnerSpecular * maxScattering(p);
                m.direct = [p](glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 c) {
                  const float tl = glm::dot(T, L);
                  const float diffuse = std::sqrt(std::max(0.0f, 1.0f - tl * tl));
                  const glm::vec3 specular = marschnerScattering(p, T, L, V, c) * diffuse;
                  return p.marschnerDiffuse * diffuse * c + p.marschnerSpecular * specular;
                };
                return m;
              }});
