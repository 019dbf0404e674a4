// Occupancy-ordered blending, accumulation pass (Sintorn & Assarsson 2009,
// 3.2 and 3.4): every visible hair fragment estimates its order o, the number
// of fragments in front of it in its pixel, from the eye-space depth range,
// occupancy bits and slab counts (occupancyCount: slab i's F_i fragments spread
// over its set bits, linear within a slice), and adds
//   target 0: (1 - a)^o * a * (shaded colour, 1)     (additive, fp32)
//   target 1: log2(1 - a)                             (additive: log2 prod (1 - a_i))
// with a the fragment's own alpha (the vertex colour's alpha). Its defines are
// SB_OOIT_*: the occupancy shadow's lookup uses SB_OCC_* with its own values.
#include "render/common/view.glsl"
#include "render/common/shading.glsl"
#include <shadow>
#include "render/shading/hair_shading.glsl"
#include "../occupancy/occupancy_math.glsl"  // once, with the occupancy shadow's lookup
#include "occupancy_oit_math.glsl"
#include "slots.h"

layout(binding = SB_SLOT_OOIT_RANGE) uniform sampler2D oitRange;  // x: nearest, y: -furthest depth
layout(binding = SB_SLOT_OOIT_BITS) uniform usampler2DArray oitBits;  // 128 slices per layer
layout(binding = SB_SLOT_OOIT_SLABS) uniform sampler2DArray oitSlabs;  // 4 slabs per layer

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;

layout(location = 0) out vec4 outAccum;
layout(location = 1) out vec4 outLog2T;

void main() {
  ivec2 t = ivec2(gl_FragCoord.xy);
  vec2 r = texelFetch(oitRange, t, 0).rg;
  uint bits[SB_OCC_MAX_WORDS];
  for (int i = 0; i < SB_OCC_MAX_WORDS; ++i) bits[i] = 0u;
  for (int k = 0; k < SB_OOIT_WORD_TARGETS; ++k) {
    uvec4 w = texelFetch(oitBits, ivec3(t, k), 0);
    for (int c = 0; c < 4; ++c) bits[4 * k + c] = w[c];
  }
  float slabs[SB_OCC_MAX_SLABS];
  for (int i = 0; i < SB_OCC_MAX_SLABS; ++i) slabs[i] = 0.0;
  for (int m = 0; m < SB_OOIT_SLAB_TARGETS; ++m) {
    vec4 f = texelFetch(oitSlabs, ivec3(t, m), 0);
    for (int c = 0; c < 4; ++c) slabs[4 * m + c] = f[c];
  }
  // Paper 3.2: slabs before the fragment's own, plus F_i / B_total * B_before
  // within it, interpolated linearly inside the fragment's slice.
  // order=paper: the printed formula, without the within-slice spread;
  // order=printed: the printed formula with it, the fragment's own share kept.
#if SB_OOIT_ORDER == 1
  float o = oitOrderPaper(gl_FragCoord.z, r.x, -r.y, bits, slabs, SB_OOIT_SLICES, SB_OOIT_SLABS);
#elif SB_OOIT_ORDER == 2
  float o = oitOrderPrinted(gl_FragCoord.z, r.x, -r.y, bits, slabs, SB_OOIT_SLICES, SB_OOIT_SLABS);
#else
  float o = oitOrder(gl_FragCoord.z, r.x, -r.y, bits, slabs, SB_OOIT_SLICES, SB_OOIT_SLABS);
#endif
  float a = clamp(vColor.a, 0.0, 1.0);
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  // Paper 3.4: color_out = (1 - alpha)^o * alpha * color_in, color_in.a = 1.
  float weight = oitWeight(a, o);
  outAccum = vec4(c * weight, weight);
  outLog2T = vec4(oitLog2Transmittance(a), 0.0, 0.0, 0.0);
}
