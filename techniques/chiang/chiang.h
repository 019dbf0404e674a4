// The GLSL math of chiang.glsl, compiled as C++ for tests and the CPU references, and the
// table of h-averaged azimuthal lobes it reads, built from pbr/'s Ap and Np.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "techniques/chiang/uniforms.h"

namespace sb {

// The h-averaged A_p N_p of the fibre with this azimuthal roughness and index (chiang.glsl's
// axes and layout), built once per (beta_n, eta) in a process and kept.
const std::vector<float>& chiangLobeTable(float betaN, float eta);
// The fraction of the light crossing a fibre of this colour that it stops, as the shadow
// techniques' shadow_alpha: 1 - the luminance of TT's attenuation A_1 = (1 - F)^2 T averaged
// over h in [-1, 1] at normal incidence, T = exp(-sigma_a 2 cos(gamma_t)) over the refracted
// chord of a unit-radius fibre (pbr::hair::Ap's, sigma_a from the colour as the tracer derives
// it): the light the tracer's shadow rays let through a fibre, one definition for both sides.
float chiangShadowAlpha(glm::vec3 color, float betaN, float eta);
// sqrt(sigma_a)'s range in the table: the colour clamped to 1e-3 as the tracer clamps it.
float chiangXMax(float betaN);

namespace glsl {
using glm::abs;
using glm::clamp;
using glm::cos;
using glm::dot;
using glm::exp;
using glm::length;
using glm::log;
using glm::max;
using glm::min;
using glm::mix;
using glm::sqrt;
using glm::vec2;
using glm::vec3;
using glm::vec4;
// The shader's storage buffer, here a pointer set by chiangShade for the calling thread.
inline thread_local const float* chiangTable = nullptr;
#define SB_INLINE inline
#include "techniques/chiang/chiang.glsl"
#undef SB_INLINE
}  // namespace glsl

// chiang.glsl's value on the CPU for the model's block and table (shading.glsl's
// shadingDirect): h-averaged f cos times pi.
glm::vec3 chiangShade(const ChiangParams& p, const std::vector<float>& table, glm::vec3 T,
                      glm::vec3 L, glm::vec3 V, glm::vec3 color);

}  // namespace sb
