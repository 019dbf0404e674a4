// The hair shading models of the final passes (`--shading NAME:key=value,...`): Kajiya-Kay
// (techniques/kajiya_kay/), Marschner et al. 2003 (techniques/marschner/), the
// artist-friendly model of Sadeghi et al. 2010 as the thesis implements it (techniques/sadeghi/)
// and the path-traced reference's fibre, Chiang et al. 2016 (techniques/chiang/).
// The math is in each folder's .glsl, shared with the CPU tests; this is the choice and its
// parameters, read from the spec and handed to the shaders as uniforms.
#pragma once

#include <functional>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sb {

class OptionReader;

enum class ShadingKind {
  KajiyaKay = 0,
  Marschner = 1,
  Sadeghi = 2,
  Chiang = 3
};  // SB_SHADING_MODEL

struct ShadingModel {
  ShadingKind kind = ShadingKind::KajiyaKay;
  std::string spec;  // canonical NAME[:options] as given (fromSpec)
  // Diffuse and specular weights, Kajiya-Kay's exponent, ambient.
  glm::vec4 material{0.8f, 0.35f, 40.0f, 0.12f};
  // Marschner: (alpha_R, alpha_TT, alpha_TRT, eta), (beta_R, beta_TT, beta_TRT, caustic floor).
  // Sadeghi: (alpha_R, alpha_TT, alpha_TRT, glint half angle), (beta_R, beta_TT, beta_TRT,
  // xi_TT), intensities (I_R, I_TT, I_TRT, I_g), glint width xi_g. Angles in radians.
  // Chiang: M_p's variances (R, TT, TRT, higher orders); sin and cos of alpha and 2 alpha;
  // sin and cos of 4 alpha, sqrt(sigma_a) per |ln colour|, the table's range of sqrt(sigma_a)
  // (chiang.glsl); eta and beta_n choose its table, specularBound bounds its value.
  glm::vec4 shift{0.0f}, width{1.0f}, intensity{0.0f};
  float glintWidth = 0.1f;
  float eta = 1.55f, betaN = 0.3f, specularBound = 0.0f;
  // Set by a model whose fibre defines how much light a strand stops (chiang:opacity=fibre):
  // the shadow alpha of hair of this mean colour; empty: the scene's shadow_alpha.
  std::function<float(glm::vec3)> fibreShadowAlpha;
  // chiang:scattering=dual (techniques/chiang/dual.glsl): multiple scattering by Zinke et al.
  // 2008's dual scattering, with its forward and backward density factors d_f, d_b.
  bool dualScattering = false;
  float densityF = 0.7f, densityB = 0.7f;

  // From the registry (techniques/common/unit.h): throws InputError naming the model and the
  // option (unknown name or option, out of range).
  static ShadingModel fromSpec(const std::string& spec);
  // Marschner's and Sadeghi's lobes from their options diffuse, specular, alpha and beta.
  static ShadingModel withLobes(const OptionReader& o);
  // The largest value the specular factor can take (the shader's bounds on cos^2(theta_d)
  // included): the colour invariant's bound.
  float maxSpecular() const;
  // The shadow alpha the techniques and references use for this scene: the fibre's where the
  // model derives one (from the strands' mean colour), else the scene's.
  float shadowAlpha(const Scene& scene) const;
};

constexpr float kDegree = 3.14159265358979f / 180.0f;

}  // namespace sb
