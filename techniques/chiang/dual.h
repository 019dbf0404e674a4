// Dual scattering on the Chiang fibre (dual.glsl): the fibre's averages the paper precomputes,
// built on the CPU from chiang's table, and dual.glsl compiled as C++ for tests.
#pragma once

#include <glm/glm.hpp>
#include <vector>

#include "techniques/chiang/chiang.h"

namespace sb {

// The paper's averages at one absorption and |sin theta| (Zinke et al. 2008, section 4), in
// u = theta_i + theta_o: the forward and backward attenuations a_f, a_b (the h-averaged
// fibre's energy scattered into the forward, |phi| > pi/2, and backward half of the sphere),
// their lobe-weighted mean shifts alpha_f, alpha_b and widths beta_f, beta_b, and the
// neighbourhood's back-scattering A_b (A_1 + A_3), shift Delta_b and variance sigma_b^2 for
// density factor d_b.
struct DualTerms {
  double af = 0, ab = 0, alphaF = 0, alphaB = 0, betaF = 0, betaB = 0;
  double Ab = 0, deltaB = 0, sigmaB2 = 0;
};
DualTerms dualTerms(const ChiangParams& p, int x, int sinTheta);

// chiang's table with dual.glsl's appended (its layout there), for chiang's block p
// (scattering=dual); built once per set of parameters in a process and kept.
const std::vector<float>& dualTable(const ChiangParams& p);

namespace glsl {
using glm::pow;
#define SB_INLINE inline
#include "techniques/chiang/dual.glsl"
#undef SB_INLINE
}  // namespace glsl

// dual.glsl's value on the CPU: pi times f cos with the light's visibility in it.
glm::vec3 dualShade(const ChiangParams& p, glm::vec3 T, glm::vec3 L, glm::vec3 V, glm::vec3 color,
                    float visibility, float strandAlpha);

}  // namespace sb
