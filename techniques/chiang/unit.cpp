// --shading chiang.
#include "render/common/unit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pbr/hair_bsdf.h"
#include "techniques/chiang/chiang.h"
#include "techniques/chiang/dual.h"
#include "techniques/chiang/slots.h"

namespace sb {
namespace {

// M_p's largest value for variance v: I0(a) e^-b <= e^(a - b) <= e^(1/v), times the
// normalisation csch(1/v) / (2v).
double mpBound(double v) { return 1.0 / (v * -std::expm1(-2.0 / v)); }

// What dual scattering adds to the colour invariant's bound (dual.glsl): the direct light's
// back-scatter d_b A_b M_b and, with T_f - visibility <= d_f, the forward-scattered light's
// d_f^2 (pi sum of M_p N^G_p + pi d_b A_b M_b); each M at its narrowest variance.
double dualBound(const ChiangParams& p) {
  const std::vector<float>& t = dualTable(p);
  double ab = 0, vb = SB_DUAL_MAX_VARIANCE;
  for (int i = 0; i < SB_CHIANG_X * SB_CHIANG_SIN; ++i) {
    ab = std::max(ab, double(t[SB_DUAL_PARAMS + i * SB_DUAL_FIELDS + 2]));
    vb = std::min(vb, double(t[SB_DUAL_PARAMS + i * SB_DUAL_FIELDS + 5]));
  }
  const double back = ab * mpBound(std::max(vb, 1e-4));
  const std::size_t lobe = SB_DUAL_LOBES / SB_CHIANG_LOBES;
  double global = 0;
  for (int l = 0; l < SB_CHIANG_LOBES; ++l) {
    const auto first = t.begin() + SB_DUAL_LOBES + l * lobe;
    global += mpBound(p.chiangVariance[l]) * *std::max_element(first, first + lobe);
  }
  const double pi = std::numbers::pi;
  const double df = p.chiangDensityF, db = p.chiangDensityB;
  return db * back + df * df * (pi * global + pi * db * back);
}

struct O {
  float betaM, betaN, alpha, eta, ambient, densityF, densityB;
  bool fibreOpacity, dual;
};
const OptionTable<O> kOptions(
    {opt::number(&O::betaM, "beta_m", "0.3", 0.01, 1, "longitudinal roughness, 0.01..1"),
     opt::number(&O::betaN, "beta_n", "0.3", 0.01, 1, "azimuthal roughness, 0.01..1"),
     opt::number(&O::alpha, "alpha", "2", -45, 45,
                 "tilt of the cuticle scales in degrees, -45..45"),
     opt::number(&O::eta, "eta", "1.55", 1.01, 3, "index of refraction of the fibre, 1.01..3"),
     opt::number(&O::ambient, "ambient", "0", 0, 1,
                 "ambient term, a fraction of the hair colour (the tracer has none), "
                 "0..1"),
     opt::choice(&O::fibreOpacity, "opacity", "scene", {{"scene", false}, {"fibre", true}},
                 "the strands' shadow alpha: the scene's shadow_alpha, or the light "
                 "this fibre stops (1 - its mean forward transmittance A_1)"),
     opt::choice(&O::dual, "scattering", "single", {{"single", false}, {"dual", true}},
                 "single scattering, or Zinke et al. 2008's dual scattering approximation of "
                 "multiple scattering, fed by the shadow technique's visibility "
                 "(techniques/chiang/dual.glsl)"),
     opt::number(&O::densityF, "d_f", "0.7", 0, 1,
                 "dual scattering's forward density factor d_f, 0..1"),
     opt::number(&O::densityB, "d_b", "0.7", 0, 1,
                 "dual scattering's backward density factor d_b, 0..1")});
}  // namespace
}  // namespace sb

SB_TECHNIQUE({.options = kOptions.infos(), .makeShading = [](const OptionReader& r) {
                const O o = kOptions.read(r);
                pbr::HairParams hp;
                hp.betaM = o.betaM;
                hp.betaN = o.betaN;
                hp.alphaDeg = o.alpha;
                hp.eta = o.eta;
                const pbr::HairBsdf bsdf(hp);  // the same variances as the tracer's
                ChiangParams p{};
                for (int l = 0; l < 4; ++l)
                  p.chiangVariance[l] = static_cast<float>(bsdf.variance(l));
                const float a = hp.alphaDeg * kDegree;
                p.chiangTilt1 = {std::sin(a), std::cos(a), std::sin(2 * a), std::cos(2 * a)};
                // sqrt(sigma_a) = |ln c| / divisor: the divisor's inverse is sqrt(sigma_a) at c =
                // 1/e.
                const float inverse =
                    std::sqrt(pbr::sigmaAFromReflectance(glm::vec3(std::exp(-1.0f)), hp.betaN).x);
                p.chiangTilt4 = {std::sin(4 * a), std::cos(4 * a), inverse, chiangXMax(hp.betaN)};
                p.chiangBetaN = hp.betaN;
                p.chiangEta = hp.eta;
                p.chiangDensityF = o.densityF;
                p.chiangDensityB = o.densityB;
                p.chiangDualScattering = o.dual ? 1 : 0;
                p.chiangFibreOpacity = o.fibreOpacity ? 1 : 0;
                p.chiangOpacityRow = o.dual ? SB_DUAL_OPACITY : SB_CHIANG_OPACITY;
                // Dual scattering reads chiang's table with its own appended (dual.glsl).
                const std::vector<float>& lobes = chiangLobeTable(hp.betaN, hp.eta);
                const std::vector<float>& table = o.dual ? dualTable(p) : lobes;
                ShadingModel m;
                m.tables.push_back({SB_SLOT_CHIANG_TABLE, &table});
                m.ambient = o.ambient;
                // The colour invariant's bound: pi times each lobe's largest M_p and table entry.
                const std::size_t lobe = std::size_t(SB_CHIANG_X) * SB_CHIANG_SIN * SB_CHIANG_PHI;
                double bound = 0;
                for (int l = 0; l < SB_CHIANG_LOBES; ++l)
                  bound +=
                      mpBound(p.chiangVariance[l]) *
                      *std::max_element(lobes.begin() + l * lobe, lobes.begin() + (l + 1) * lobe);
                m.maxDirect = static_cast<float>(std::numbers::pi * bound);
                if (o.dual) m.maxDirect += static_cast<float>(dualBound(p));
                m.setParams(p);
                // The CPU form is single scattering (the references' direct light).
                m.direct = [p, &lobes](glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 c) {
                  return chiangShade(p, lobes, T, L, V, c);
                };
                if (o.fibreOpacity) {
                  // A fragment's colour is divided by its opacity (shading.glsl's chiangOpacity):
                  // most for the clearest fibre; the CPU form over the fibre's shadow alpha
                  // likewise.
                  m.maxDirect /= chiangShadowAlpha(glm::vec3(1.0f), hp.betaN, hp.eta);
                  m.fibreShadowAlpha = [betaN = hp.betaN, eta = hp.eta](glm::vec3 c) {
                    return chiangShadowAlpha(c, betaN, eta);
                  };
                  m.direct = [p, &lobes, alpha = m.fibreShadowAlpha](glm::vec3 T, glm::vec3 L,
                                                                     glm::vec3 V, glm::vec3 c) {
                    return chiangShade(p, lobes, T, L, V, c) / alpha(c);
                  };
                }
                return m;
              }});
