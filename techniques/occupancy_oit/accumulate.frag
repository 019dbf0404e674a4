// Occupancy-ordered blending, accumulation pass (Sintorn & Assarsson 2009,
// 3.2 and 3.4): every visible hair fragment estimates its order o, the number
// of fragments in front of it in its pixel, from the eye-space depth range,
// occupancy bits and slab counts (occupancyCount: slab i's F_i fragments spread
// over its set bits, linear within a slice), and adds
//   target 0: (1 - a)^o * a * (shaded colour, 1)     (additive, fp32)
//   target 1: log2(1 - a)                             (additive: log2 prod (1 - a_i))
// with a the fragment's own alpha (the vertex colour's alpha). Its defines are
// SB_OOIT_*: the occupancy shadow's lookup uses SB_OCC_* with its own values.
#include "../common/view.glsl"
#include "../common/shading.glsl"
#include <shadow>
#include "../kajiya_kay/hair_shading.glsl"
// Also included by the occupancy shadow's lookup (<shadow>): only once.
#ifndef SB_OCC_MAX_WORDS
#include "../occupancy/occupancy_math.glsl"
#endif
#include "occupancy_oit_math.glsl"

layout(binding = 20) uniform sampler2D oitRange;  // x: nearest depth, y: -furthest depth
layout(binding = 21) uniform usampler2D oitBits0;
#if SB_OOIT_WORD_TARGETS > 1
layout(binding = 22) uniform usampler2D oitBits1;
#endif
#if SB_OOIT_WORD_TARGETS > 2
layout(binding = 23) uniform usampler2D oitBits2;
#endif
#if SB_OOIT_WORD_TARGETS > 3
layout(binding = 24) uniform usampler2D oitBits3;
#endif
layout(binding = 25) uniform sampler2D oitSlabs0;
#if SB_OOIT_SLAB_TARGETS > 1
layout(binding = 26) uniform sampler2D oitSlabs1;
#endif
#if SB_OOIT_SLAB_TARGETS > 2
layout(binding = 27) uniform sampler2D oitSlabs2;
#endif
#if SB_OOIT_SLAB_TARGETS > 3
layout(binding = 28) uniform sampler2D oitSlabs3;
#endif

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
  uvec4 w = texelFetch(oitBits0, t, 0);
  bits[0] = w.x; bits[1] = w.y; bits[2] = w.z; bits[3] = w.w;
#if SB_OOIT_WORD_TARGETS > 1
  w = texelFetch(oitBits1, t, 0);
  bits[4] = w.x; bits[5] = w.y; bits[6] = w.z; bits[7] = w.w;
#endif
#if SB_OOIT_WORD_TARGETS > 2
  w = texelFetch(oitBits2, t, 0);
  bits[8] = w.x; bits[9] = w.y; bits[10] = w.z; bits[11] = w.w;
#endif
#if SB_OOIT_WORD_TARGETS > 3
  w = texelFetch(oitBits3, t, 0);
  bits[12] = w.x; bits[13] = w.y; bits[14] = w.z; bits[15] = w.w;
#endif
  float slabs[SB_OCC_MAX_SLABS];
  for (int i = 0; i < SB_OCC_MAX_SLABS; ++i) slabs[i] = 0.0;
  vec4 f = texelFetch(oitSlabs0, t, 0);
  slabs[0] = f.x; slabs[1] = f.y; slabs[2] = f.z; slabs[3] = f.w;
#if SB_OOIT_SLAB_TARGETS > 1
  f = texelFetch(oitSlabs1, t, 0);
  slabs[4] = f.x; slabs[5] = f.y; slabs[6] = f.z; slabs[7] = f.w;
#endif
#if SB_OOIT_SLAB_TARGETS > 2
  f = texelFetch(oitSlabs2, t, 0);
  slabs[8] = f.x; slabs[9] = f.y; slabs[10] = f.z; slabs[11] = f.w;
#endif
#if SB_OOIT_SLAB_TARGETS > 3
  f = texelFetch(oitSlabs3, t, 0);
  slabs[12] = f.x; slabs[13] = f.y; slabs[14] = f.z; slabs[15] = f.w;
#endif
  // Paper 3.2: slabs before the fragment's own, plus F_i / B_total * B_before
  // within it, interpolated linearly inside the fragment's slice.
  float o = oitOrder(gl_FragCoord.z, r.x, -r.y, bits, slabs, SB_OOIT_SLICES, SB_OOIT_SLABS);
  float a = clamp(vColor.a, 0.0, 1.0);
  vec3 c = shadeHair(vWorldPos, vTangent, vColor.rgb);
  // Paper 3.4: color_out = (1 - alpha)^o * alpha * color_in, color_in.a = 1.
  float weight = oitWeight(a, o);
  outAccum = vec4(c * weight, weight);
  outLog2T = vec4(oitLog2Transmittance(a), 0.0, 0.0, 0.0);
}
