// --shading sadeghi.
#include "render/common/unit.h"

#include <algorithm>
#include <cmath>

#include "techniques/sadeghi/sadeghi.h"

namespace sb {
namespace {
struct O {
  LobeOptions lobes;
  float iR, iTT, iTRT, ttWidth, glint, glintAngle, glintWidth, ambient;
};
const OptionTable<O> kOptions(
    {opt::lobes(&O::lobes, "weight of the Kajiya-Kay diffuse term (the thesis: 0.4), 0..4",
                "weight of the specular sum (Listing 2: 1, R + TT + TRT unweighted), 0..4", "1"),
     opt::number(&O::iR, "i_r", "1", 0, 10, "intensity of the primary highlight R, 0..10"),
     opt::number(&O::iTT, "i_tt", "1", 0, 10, "intensity of the transmission TT, 0..10"),
     opt::number(&O::iTRT, "i_trt", "1", 0, 10, "intensity of the secondary highlight TRT, 0..10"),
     opt::number(&O::ttWidth, "tt_width", "10", 1, 90, "azimuthal width of TT in degrees, 1..90"),
     opt::number(&O::glint, "glint", "0.5", 0, 10, "relative intensity of the glints I_g, 0..10"),
     opt::number(&O::glintAngle, "glint_angle", "35", 0, 90,
                 "glints' half angle in degrees (the thesis: 30..45), 0..90"),
     opt::number(&O::glintWidth, "glint_width", "0", 0, 90,
                 "azimuthal width of the glints in degrees; 0: tt_width (Listing 2's one "
                 "azi_width), 0..90"),
     opt::number(&O::ambient, "ambient", "0", 0, 1,
                 "ambient term, a fraction of the hair colour (Listing 2: none), 0..1")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShading = [](const OptionReader& r) {
                const O o = kOptions.read(r);
                const ShadingLobes lobes = ShadingLobes::from(o.lobes);
                SadeghiParams p{};
                p.sadeghiAlpha = lobes.alpha;
                p.sadeghiBeta = lobes.beta;
                p.sadeghiIntensity = {o.iR, o.iTT, o.iTRT, o.glint};
                p.sadeghiDiffuse = lobes.diffuse;
                p.sadeghiSpecular = lobes.specular;
                p.sadeghiGlintAngle = o.glintAngle * kDegree;
                p.sadeghiTtWidth = o.ttWidth * kDegree;
                p.sadeghiGlintWidth = (o.glintWidth > 0.0f ? o.glintWidth : o.ttWidth) * kDegree;
                ShadingModel m;
                m.setParams(p);
                m.ambient = o.ambient;
                // The specular sum's largest value: every lobe at its peak, over the shader's bound
                // on cos^2(theta_d).
                const glm::vec4 i = p.sadeghiIntensity;
                m.maxDirect = p.sadeghiDiffuse +
                              p.sadeghiSpecular * ((i.x + i.y + i.z * (1.0f + i.w)) / kMinCos2);
                m.direct = [p](glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 c) {
                  const float tl = glm::dot(T, L);
                  const float diffuse = std::sqrt(std::max(0.0f, 1.0f - tl * tl));
                  return p.sadeghiDiffuse * diffuse * c +
                         p.sadeghiSpecular * sadeghiSpecular(p, T, L, V, c);
                };
                return m;
              }});
