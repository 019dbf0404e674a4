// Approximated deep shadows lookup (TressFX): over the kernel's taps of the
// hair's front depth map, (1 - alpha)^fibers for the point's depth behind
// each tap's front, Gaussian-weighted (adsm_math.glsl); 0 behind the opaque mesh.
#include "render/common/opaque_shadow.glsl"
#include "slots.h"
#include "adsm_math.glsl"

#include "uniforms.h"
layout(binding = SB_SLOT_ADSM_DEPTH) uniform sampler2D adsmDepth;  // the hair's front

float shadowVisibility(vec3 worldPos) {
  vec3 ndc;
  if (!toLightNdc(adsmViewProj, worldPos, ndc)) return 1.0;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  if (opaqueVisibility(ndc, adsmParams.x) == 0.0) return 0.0;
  int size = int(adsmParams.y);
  int kernel = int(adsmFiber.z);
  ivec2 t = min(ivec2(uv * adsmParams.y), ivec2(size - 1));
  float z = ndc.z - adsmParams.x;
  float sum = 0.0, weights = 0.0;
  for (int dy = (1 - kernel) / 2; dy <= kernel / 2; ++dy) {
    for (int dx = (1 - kernel) / 2; dx <= kernel / 2; ++dx) {
      ivec2 p = clamp(t + ivec2(dx, dy), ivec2(0), ivec2(size - 1));
      float front = texelFetch(adsmDepth, p, 0).r;
      float dz = max(z - front, 0.0) * adsmFiber.x;
      float w = adsmKernelWeight(dx, dy, kernel);
      sum += w * adsmVisibility(dz, adsmFiber.y, adsmParams.z);
      weights += w;
    }
  }
  return sum / weights;
}
