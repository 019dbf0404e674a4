#include "techniques/common/shading_model.h"

#include <algorithm>
#include <cmath>

#include "scenes/options.h"
#include "techniques/common/technique.h"

namespace sb {

namespace {

constexpr float kDegree = 3.14159265358979f / 180.0f;
// The shaders bound cos^2(theta_d) below by this (marschner.glsl, sadeghi.glsl).
constexpr float kMinCos2 = 1e-2f;

}  // namespace

const std::vector<TechniqueInfo>& shadingCatalog() {
  static const std::vector<TechniqueInfo> catalog = {
      {"kajiya-kay",
       "Kajiya & Kay 1989: diffuse sin(T,L), specular cos^shininess on the reflection cone",
       {{"diffuse", "0.8", "diffuse weight, 0..4"},
        {"specular", "0.35", "specular weight, 0..4"},
        {"shininess", "40", "specular exponent, 1..1000"}}},
      {"marschner",
       "Marschner et al. 2003: R, TT, TRT lobes, longitudinal Gaussians, azimuthal terms with "
       "Fresnel and absorption (from the strand colour)",
       {{"diffuse", "0.4", "weight of a Kajiya-Kay diffuse term (the thesis adds one), 0..4"},
        {"specular", "0.5", "weight of the scattering function, 0..4"},
        {"alpha", "-7.5",
         "R lobe's longitudinal shift in degrees (cuticle tilt; TT -alpha/2, "
         "TRT -3alpha/2), -20..20"},
        {"beta", "7.5", "R lobe's longitudinal width in degrees (TT beta/2, TRT 2beta), 1..45"},
        {"eta", "1.55", "index of refraction of the fibre, 1.01..3"},
        {"caustic", "0.5",
         "floor on |dphi/dh| bounding the TRT caustic (the paper fades it with a Gaussian), "
         "0.01..4"}}},
      {"sadeghi",
       "Sadeghi et al. 2010, the artist-friendly model as Kraft 2018 implements it (eqs. 20-24, "
       "Listing 2)",
       {{"diffuse", "0.4", "weight of the Kajiya-Kay diffuse term (the thesis: 0.4), 0..4"},
        {"specular", "0.5", "weight of the specular sum, 0..4"},
        {"alpha", "-7.5",
         "R lobe's longitudinal shift in degrees (TT -alpha/2, TRT -3alpha/2), "
         "-20..20"},
        {"beta", "7.5", "R lobe's longitudinal width in degrees (TT beta/2, TRT 2beta), 1..45"},
        {"i_r", "1", "intensity of the primary highlight R, 0..10"},
        {"i_tt", "1", "intensity of the transmission TT, 0..10"},
        {"i_trt", "1", "intensity of the secondary highlight TRT, 0..10"},
        {"tt_width", "10", "azimuthal width of TT in degrees, 1..90"},
        {"glint", "0.5", "relative intensity of the glints I_g, 0..10"},
        {"glint_angle", "35", "glints' half angle in degrees (the thesis: 30..45), 0..90"},
        {"glint_width", "5", "azimuthal width of the glints in degrees, 1..90"}}},
  };
  return catalog;
}

ShadingModel ShadingModel::fromSpec(const std::string& text) {
  const Spec spec = Spec::parse(text);
  const auto& catalog = shadingCatalog();
  const TechniqueInfo* info = nullptr;
  std::vector<std::string> names;
  for (const auto& t : catalog) {
    if (t.name == spec.name) info = &t;
    names.push_back(t.name);
  }
  if (!info) throw InputError(unknownNameMessage("shading model", spec.name, names));
  const OptionReader o(spec, info->options, "shading model '" + spec.name + "'");
  ShadingModel m;
  m.spec = text;
  auto f = [&](const char* name, double lo, double hi) {
    return static_cast<float>(o.number(name, lo, hi));
  };
  if (spec.name == "kajiya-kay") {
    m.kind = ShadingKind::KajiyaKay;
    m.material = {f("diffuse", 0, 4), f("specular", 0, 4), f("shininess", 1, 1000), 0.12f};
    return m;
  }
  const float alpha = f("alpha", -20, 20) * kDegree;
  const float beta = f("beta", 1, 45) * kDegree;
  // The paper's relations between the lobes (Marschner et al. 2003, Table 1; kept by Sadeghi).
  m.shift = {alpha, -alpha / 2.0f, -3.0f * alpha / 2.0f, 0.0f};
  m.width = {beta, beta / 2.0f, 2.0f * beta, 0.0f};
  m.material = {f("diffuse", 0, 4), f("specular", 0, 4), 0.0f, 0.12f};
  if (spec.name == "marschner") {
    m.kind = ShadingKind::Marschner;
    m.shift.w = f("eta", 1.01, 3);
    m.width.w = f("caustic", 0.01, 4);
  } else {
    m.kind = ShadingKind::Sadeghi;
    m.shift.w = f("glint_angle", 0, 90) * kDegree;
    m.width.w = f("tt_width", 1, 90) * kDegree;
    m.intensity = {f("i_r", 0, 10), f("i_tt", 0, 10), f("i_trt", 0, 10), f("glint", 0, 10)};
    m.glintWidth = f("glint_width", 1, 90) * kDegree;
  }
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
  }
  return 1.0f;
}

}  // namespace sb
