// Fourier opacity maps lookup: the optical depth in front of the point from
// its texel's coefficients, transmittance clamped to [0, 1] (fom_math.glsl);
// 0 behind the opaque mesh.
#include "render/common/opaque_shadow.glsl"
#include "slots.h"
#include "fom.glsl"

layout(binding = SB_SLOT_FOM_MAPS) uniform sampler2DArray fomMaps;  // 4 floats per layer

ivec2 fomTexel;
float fomStored(int j) { return texelFetch(fomMaps, ivec3(fomTexel, j / 4), 0)[j % 4]; }
#define SB_FOM_COEFF(j) fomStored(j)
#include "fom_math.glsl"

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(fomViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, fomParams.x) == 0.0) return 0.0;
  int size = int(fomParams.y);
  fomTexel = min(ivec2(uv * fomParams.y), ivec2(size - 1));
  float d = fomDepth(ndc.z - fomParams.x);
  return fomTransmittance(fomOpticalDepth(d, int(fomRange.z)));
}
