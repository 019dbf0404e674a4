// Parameters of moment shadow maps, for the light pass and the lookup.
#include "../common/slots.h"
layout(std140, binding = SB_SLOT_MSM_PARAMS) uniform MsmParams {
  mat4 msmViewProj;
  vec4 msmParams;  // lookup bias (light depth units), map size, shadow alpha, moment bias
  vec4 msmRange;   // the hair's near and far light depth, overestimation, 0
  ivec4 msmN;      // x: real moments beyond b0 (4, 6, 8), y: kind (0 power, 1 trig)
};
// Both passes compute a point's light depth with msmLightDepth: `precise`,
// the matrix product's sums in one written order and the division as a
// reciprocal product (mboitRcp: include mboit_math.glsl first), so that GL and
// Vulkan round alike. Measured: the lookup's depth (ndc.z of toLightNdc) was
// up to 2.4e-7 apart between the backends, with this it is bit for bit equal.

// The light's clip position of a world position, the sums in one order.
vec4 msmClip(vec3 worldPos) {
  precise vec4 c =
      ((msmViewProj[0] * worldPos.x + msmViewProj[1] * worldPos.y) + msmViewProj[2] * worldPos.z) +
      msmViewProj[3];
  return c;
}

// The light's window depth of a world position.
float msmLightDepth(vec3 worldPos) {
  precise vec4 c = msmClip(worldPos);
  precise float z = c.z * mboitRcp(c.w);
  return z;
}

// The light pass's fragment on its segment (end points e0, e1), by GL's rule
// for a line's attributes: the fragment centre projected onto the segment in
// window space, then perspective corrected. The rasterizers apply that rule
// themselves, but GL's and Vulkan's interpolated positions differ by 1-2 ulp
// (55 of 293 single-fragment texels on curly hair), which the moments' solve
// amplifies to visibility 0.02 apart; computed here from the flat end points
// and gl_FragCoord.xy (exact texel centres on both), they round alike.
// `interpolated` is kept where an end is behind the light (clipped lines).
vec3 msmSegmentPoint(vec3 e0, vec3 e1, vec2 fragXY, vec3 interpolated) {
  precise vec4 c0 = msmClip(e0);
  precise vec4 c1 = msmClip(e1);
  if (!(min(c0.w, c1.w) > 0.0)) return interpolated;
  precise vec2 w0 = (c0.xy * mboitRcp(c0.w) * 0.5 + 0.5) * msmParams.y;
  precise vec2 w1 = (c1.xy * mboitRcp(c1.w) * 0.5 + 0.5) * msmParams.y;
  precise vec2 d = w1 - w0;
  precise vec2 f = fragXY - w0;
  precise float len2 = d.x * d.x + d.y * d.y;
  precise float t = len2 > 0.0 ? clamp((f.x * d.x + f.y * d.y) * mboitRcp(len2), 0.0, 1.0) : 0.5;
  // Perspective correction: the weight of e1 in world space.
  precise float s = (t * c0.w) * mboitRcp((1.0 - t) * c1.w + t * c0.w);
  precise vec3 p = e0 + (e1 - e0) * s;
  return p;
}

// Light window depth to [-1, 1] over the hair's depth range (linear: the
// light's depth is already what the moments should resolve).
float msmDepth(float z) {
  precise float u =
      clamp((z - msmRange.x) * mboitRcp(max(msmRange.y - msmRange.x, 1e-12)), 0.0, 1.0);
  precise float d = u * 2.0 - 1.0;
  return d;
}
