// Parameters of moment shadow maps, for the light pass and the lookup.
#include "../common/slots.h"
layout(std140, binding = SB_SLOT_MSM_PARAMS) uniform MsmParams {
  mat4 msmViewProj;
  vec4 msmParams;  // lookup bias (light depth units), map size, shadow alpha, moment bias
  vec4 msmRange;   // the hair's near and far light depth, overestimation, 0
  ivec4 msmN;      // x: real moments beyond b0 (4, 6, 8), y: kind (0 power, 1 trig)
};
// Light window depth to [-1, 1] over the hair's depth range (linear: the
// light's depth is already what the moments should resolve).
float msmDepth(float z) {
  return clamp((z - msmRange.x) / max(msmRange.y - msmRange.x, 1e-12), 0.0, 1.0) * 2.0 - 1.0;
}
