// --shading chiang.
#include "techniques/common/unit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pbr/hair_bsdf.h"
#include "techniques/chiang/chiang.h"
#include "techniques/chiang/slots.h"

namespace {

// M_p's largest value for variance v: I0(a) e^-b <= e^(a - b) <= e^(1/v), times the
// normalisation csch(1/v) / (2v).
double mpBound(double v) { return 1.0 / (v * -std::expm1(-2.0 / v)); }

}  // namespace

SB_TECHNIQUE(
    {.name = "chiang",
     .family = Family::Shading,
     .folder = "chiang",
     .paper = "Chiang et al. 2016",
     .help = "Chiang et al. 2016: the path-traced reference's fibre (pbr/hair_bsdf.h, absorption "
             "from the strand colour as it derives it), longitudinal lobes evaluated, azimuthal "
             "lobes averaged over the fibre's width in a table; no diffuse term",
     .options = {opt::number("beta_m", "0.3", 0.01, 1, "longitudinal roughness, 0.01..1"),
                 opt::number("beta_n", "0.3", 0.01, 1, "azimuthal roughness, 0.01..1"),
                 opt::number("alpha", "2", -45, 45,
                             "tilt of the cuticle scales in degrees, -45..45"),
                 opt::number("eta", "1.55", 1.01, 3, "index of refraction of the fibre, 1.01..3"),
                 opt::number("ambient", "0", 0, 1,
                             "ambient term, a fraction of the hair colour (the tracer has none), "
                             "0..1"),
                 opt::choice("opacity", "scene", {"scene", "fibre"},
                             "the strands' shadow alpha: the scene's shadow_alpha, or the light "
                             "this fibre stops (1 - its mean forward transmittance A_1)")},
     .makeShading = [](const OptionReader& o) {
       const auto f = [&](const char* name) { return static_cast<float>(o.number(name)); };
       pbr::HairParams hp;
       hp.betaM = f("beta_m");
       hp.betaN = f("beta_n");
       hp.alphaDeg = f("alpha");
       hp.eta = f("eta");
       const pbr::HairBsdf bsdf(hp);  // the same variances as the tracer's
       ChiangParams p{};
       for (int l = 0; l < 4; ++l) p.chiangVariance[l] = static_cast<float>(bsdf.variance(l));
       const float a = hp.alphaDeg * kDegree;
       p.chiangTilt1 = {std::sin(a), std::cos(a), std::sin(2 * a), std::cos(2 * a)};
       // sqrt(sigma_a) = |ln c| / divisor: the divisor's inverse is sqrt(sigma_a) at c = 1/e.
       const float inverse =
           std::sqrt(pbr::sigmaAFromReflectance(glm::vec3(std::exp(-1.0f)), hp.betaN).x);
       p.chiangTilt4 = {std::sin(4 * a), std::cos(4 * a), inverse, chiangXMax(hp.betaN)};
       const std::vector<float>& table = chiangLobeTable(hp.betaN, hp.eta);
       ShadingModel m;
       m.setParams(p);
       m.tables.push_back({SB_SLOT_CHIANG_TABLE, &table});
       m.ambient = f("ambient");
       // The colour invariant's bound: pi times each lobe's largest M_p and table entry.
       const std::size_t lobe = table.size() / SB_CHIANG_LOBES;
       double bound = 0;
       for (int l = 0; l < SB_CHIANG_LOBES; ++l)
         bound += mpBound(p.chiangVariance[l]) *
                  *std::max_element(table.begin() + l * lobe, table.begin() + (l + 1) * lobe);
       m.maxDirect = static_cast<float>(std::numbers::pi * bound);
       m.direct = [p, &table](glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 c) {
         return chiangShade(p, table, T, L, V, c);
       };
       if (o.choice("opacity") == "fibre")
         m.fibreShadowAlpha = [betaN = hp.betaN, eta = hp.eta](glm::vec3 c) {
           return chiangShadowAlpha(c, betaN, eta);
         };
       return m;
     }});
