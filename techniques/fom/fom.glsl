// Parameters of Fourier opacity maps, for the accumulation passes and the lookup.
#include "slots.h"
layout(std140, binding = SB_SLOT_FOM_PARAMS) uniform FomParams {
  mat4 fomViewProj;
  vec4 fomParams;  // bias (light depth units), map size, shadow alpha, 0
  vec4 fomRange;   // the hair's near and far light depth, frequencies n, 0
};
// Normalised depth d in [0, 1] over the hair's depth range.
float fomDepth(float z) { return (z - fomRange.x) / max(fomRange.y - fomRange.x, 1e-12); }
