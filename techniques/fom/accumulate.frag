// Every hair fragment adds its Fourier coefficients (fom_math.glsl) to the
// stored floats of its texel, 4 per target, additive blending; this pass
// writes targets SB_FOM_FIRST .. SB_FOM_FIRST + SB_FOM_TARGETS - 1.
#include "fom.glsl"
#include "fom_math.glsl"

layout(location = 0) out vec4 fomOut[SB_FOM_TARGETS];

void main() {
  float d = clamp(fomDepth(gl_FragCoord.z), 0.0, 1.0);
  float w = fomAbsorption(fomParams.z);
  int last = 2 * int(fomRange.z);
  for (int t = 0; t < SB_FOM_TARGETS; ++t) {
    vec4 v = vec4(0.0);
    for (int c = 0; c < 4; ++c) {
      int j = 4 * (SB_FOM_FIRST + t) + c;
      if (j <= last) v[c] = fomCoefficient(j, d, w);
    }
    fomOut[t] = v;
  }
}
