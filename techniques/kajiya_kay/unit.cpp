// --shading kajiya-kay.
#include "render/common/unit.h"

#include "techniques/kajiya_kay/kajiya_kay.h"
#include "techniques/kajiya_kay/uniforms.h"

namespace sb {
namespace {
struct O {
  float diffuse, specular, shininess, ambient;
};
const OptionTable<O> kOptions(
    {opt::number(&O::diffuse, "diffuse", "0.8", 0, 4, "diffuse weight, 0..4"),
     opt::number(&O::specular, "specular", "0.35", 0, 4, "specular weight, 0..4"),
     opt::number(&O::shininess, "shininess", "40", 1, 1000, "specular exponent, 1..1000"),
     opt::number(&O::ambient, "ambient", "0.12", 0, 1,
                 "ambient term, a fraction of the hair colour (0: none, as the "
                 "path-traced reference has), 0..1")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShading = [](const OptionReader& r) {
                const O o = kOptions.read(r);
                KajiyaKayParams p{};
                p.kajiyaKayDiffuse = o.diffuse;
                p.kajiyaKaySpecular = o.specular;
                p.kajiyaKayShininess = o.shininess;
                ShadingModel m;
                m.setParams(p);
                m.ambient = o.ambient;
                m.maxDirect = p.kajiyaKayDiffuse + p.kajiyaKaySpecular * 1.0f;  // both factors <= 1
                m.direct = [p](glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 c) {
                  const glm::vec2 kk = glsl::kajiyaKay(T, L, V, p.kajiyaKayShininess);
                  return p.kajiyaKayDiffuse * kk.x * c + glm::vec3(p.kajiyaKaySpecular * kk.y);
                };
                return m;
              }});
