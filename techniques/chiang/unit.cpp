// --shading chiang.
#include "render/common/unit.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "pbr/hair_bsdf.h"
#include "techniques/chiang/chiang.h"
#include "techniques/chiang/dual.h"

namespace {

// M_p's largest value for variance v: I0(a) e^-b <= e^(a - b) <= e^(1/v), times the
// normalisation csch(1/v) / (2v).
double mpBound(double v) { return 1.0 / (v * -std::expm1(-2.0 / v)); }

// What dual scattering adds to the colour invariant's bound (dual.glsl): the direct light's
// back-scatter d_b A_b M_b and, with T_f - visibility <= d_f, the forward-scattered light's
// d_f^2 (pi sum of M_p N^G_p + pi d_b A_b M_b); each M at its narrowest variance.
double dualBound(const sb::ShadingModel& m) {
  const std::vector<float>& t = sb::dualTable(m);
  double ab = 0, vb = SB_DUAL_MAX_VARIANCE;
  for (int i = 0; i < SB_CHIANG_X * SB_CHIANG_SIN; ++i) {
    ab = std::max(ab, double(t[SB_DUAL_PARAMS + i * SB_DUAL_FIELDS + 2]));
    vb = std::min(vb, double(t[SB_DUAL_PARAMS + i * SB_DUAL_FIELDS + 5]));
  }
  const double back = ab * mpBound(std::max(vb, 1e-4));
  const std::size_t lobe = SB_DUAL_LOBES / SB_CHIANG_LOBES;
  double global = 0;
  for (int p = 0; p < SB_CHIANG_LOBES; ++p) {
    const auto first = t.begin() + SB_DUAL_LOBES + p * lobe;
    global += mpBound(m.shift[p]) * *std::max_element(first, first + lobe);
  }
  const double pi = std::numbers::pi;
  return m.densityB * back + m.densityF * m.densityF * (pi * global + pi * m.densityB * back);
}

}  // namespace

namespace sb {
namespace {
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

SB_TECHNIQUE(
    {.name = "chiang",
     .family = Family::Shading,
     .folder = "chiang",
     .paper = "Chiang et al. 2016",
     .help = "Chiang et al. 2016: the path-traced reference's fibre (pbr/hair_bsdf.h, absorption "
             "from the strand colour as it derives it), longitudinal lobes evaluated, azimuthal "
             "lobes averaged over the fibre's width in a table; no diffuse term",
     .options = kOptions.infos(),
     .makeShading = [](const OptionReader& r) {
       const O o = kOptions.read(r);
       pbr::HairParams hp;
       hp.betaM = o.betaM;
       hp.betaN = o.betaN;
       hp.alphaDeg = o.alpha;
       hp.eta = o.eta;
       const pbr::HairBsdf bsdf(hp);  // the same variances as the tracer's
       ShadingModel m;
       m.kind = ShadingKind::Chiang;
       m.eta = hp.eta;
       m.betaN = hp.betaN;
       m.material = {0.0f, 1.0f, 0.0f, o.ambient};
       for (int p = 0; p < 4; ++p) m.shift[p] = static_cast<float>(bsdf.variance(p));
       const float a = hp.alphaDeg * kDegree;
       m.width = {std::sin(a), std::cos(a), std::sin(2 * a), std::cos(2 * a)};
       // sqrt(sigma_a) = |ln c| / divisor: the divisor's inverse is sqrt(sigma_a) at c = 1/e.
       const float inverse =
           std::sqrt(pbr::sigmaAFromReflectance(glm::vec3(std::exp(-1.0f)), hp.betaN).x);
       m.intensity = {std::sin(4 * a), std::cos(4 * a), inverse, chiangXMax(hp.betaN)};
       // The colour invariant's bound: pi times each lobe's largest M_p and table entry.
       const std::vector<float>& table = chiangLobeTable(m.betaN, m.eta);
       const std::size_t lobe = std::size_t(SB_CHIANG_X) * SB_CHIANG_SIN * SB_CHIANG_PHI;
       double bound = 0;
       for (int p = 0; p < SB_CHIANG_LOBES; ++p)
         bound += mpBound(m.shift[p]) *
                  *std::max_element(table.begin() + p * lobe, table.begin() + (p + 1) * lobe);
       m.specularBound = static_cast<float>(std::numbers::pi * bound);
       if (o.dual) {
         m.dualScattering = true;
         m.densityF = o.densityF;
         m.densityB = o.densityB;
         m.specularBound += dualBound(m);
       }
       if (o.fibreOpacity) {
         // A fragment's colour is divided by its opacity (chiangOpacity): most for the
         // clearest fibre.
         m.specularBound /= chiangShadowAlpha(glm::vec3(1.0f), m.betaN, m.eta);
         m.fibreShadowAlpha = [betaN = m.betaN, eta = m.eta](glm::vec3 c) {
           return chiangShadowAlpha(c, betaN, eta);
         };
       }
       return m;
     }});
