// The hair shading model of the final passes (`--shading NAME:key=value,...`), a unit like the
// shadow and transparency techniques: each model's folder (`strandbench list`) holds its math
// (.glsl, compiled as C++ for its CPU form), its shading.glsl (bound as
// <shading> in the hair passes, render/shading/hair_shading.glsl), its own uniform block
// (uniforms.h) and the descriptor whose makeShading fills this. Nothing here names a model.
#pragma once

#include <cstddef>
#include <cstring>
#include <functional>
#include <glm/glm.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "scenes/scene.h"

namespace sb {

struct ShadingModel {
  std::string spec;    // canonical NAME[:options] as given (fromSpec)
  std::string shader;  // its GLSL, bound as <shading>: defines shadingDirect(T, L, V, color)
  // Its uniform block's bytes (the folder's uniforms.h), bound at SB_SLOT_SHADING_MODEL.
  std::vector<std::byte> params;
  // A storage buffer of floats the model's GLSL reads (a table), at the slot its folder
  // names; the data lives as long as the process (a model's tables are built once and kept).
  struct Table {
    int slot = 0;
    const std::vector<float>* data = nullptr;
  };
  std::vector<Table> tables;
  float ambient = 0.12f;  // a fraction of the hair colour, added once, unshadowed
  // shadingDirect on the CPU (the references shade with it): one light of unit colour, T the
  // tangent, L towards the light, V towards the eye.
  std::function<glm::vec3(glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 color)> direct;
  // The largest value a channel of `direct` can take (colour <= 1): the colour invariant's bound.
  float maxDirect = 1.0f;
  // Set by a model whose fibre defines how much light a strand stops (its opacity option):
  // the shadow alpha of hair of this mean colour; empty: the scene's shadow_alpha.
  std::function<float(glm::vec3)> fibreShadowAlpha;

  // From the registry (render/common/unit.h): throws InputError naming the model and the
  // option (unknown name or option, out of range).
  static ShadingModel fromSpec(const std::string& spec);
  // The shadow alpha the techniques and references use for this scene: the fibre's where the
  // model derives one (from the strands' mean colour), else the scene's.
  float shadowAlpha(const Scene& scene) const;

  // The uniform block as the C++ struct of its uniforms.h (a model's factory and its tests).
  template <class Block>
  void setParams(const Block& b) {
    params.resize(sizeof b);
    std::memcpy(params.data(), &b, sizeof b);
  }
  template <class Block>
  Block paramsAs() const {
    if (params.size() != sizeof(Block)) throw std::logic_error(spec + ": not this model's block");
    Block b;
    std::memcpy(&b, params.data(), sizeof b);
    return b;
  }
};

// The lobe options of the lobe models as given: diffuse, specular, and alpha and beta in
// degrees (opt::lobes below binds them to a model's Options member).
struct LobeOptions {
  float diffuse, specular, alpha, beta;
};

// The lobes of Marschner et al. 2003 that later models keep (Table 1), from their options,
// in radians.
struct ShadingLobes {
  glm::vec4 alpha{0.0f};  // alpha_R, alpha_TT, alpha_TRT, 0
  glm::vec4 beta{0.0f};   // beta_R, beta_TT, beta_TRT, 0
  float diffuse = 0, specular = 0;
  static ShadingLobes from(const LobeOptions& o);
};

// The lobe models' shaders bound cos^2(theta_d) below by this.
constexpr float kMinCos2 = 1e-2f;

constexpr float kDegree = 3.14159265358979f / 180.0f;

namespace opt {
// The lobe options of the lobe models: diffuse, specular, alpha and beta, bound to
// their Options' LobeOptions member; the models' own options follow them in their tables.
template <class S>
std::vector<Option<S>> lobes(LobeOptions S::*m, std::string diffuseHelp, std::string specularHelp,
                             std::string specularDefault = "0.5") {
  using L = LobeOptions;
  return nested(
      m, group<L>({number(&L::diffuse, "diffuse", "0.4", 0, 4, std::move(diffuseHelp)),
                   number(&L::specular, "specular", std::move(specularDefault), 0, 4,
                          std::move(specularHelp)),
                   number(&L::alpha, "alpha", "-7.5", -20, 20,
                          "R lobe's longitudinal shift in degrees (cuticle tilt; TT -alpha/2, "
                          "TRT -3alpha/2), -20..20"),
                   number(&L::beta, "beta", "7.5", 1, 45,
                          "R lobe's longitudinal width in degrees (TT beta/2, TRT 2beta), "
                          "1..45")}));
}
}  // namespace opt

}  // namespace sb
