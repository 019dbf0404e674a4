// Parameters of moment shadow maps, for the light pass and the lookup.
#include "render/common/light_space.glsl"
#include "slots.h"
#include "uniforms.h"
// Both passes compute a point's light depth with msmLightDepth: `precise`,
// the matrix product's sums in one written order (clipOf) and the division as a
// reciprocal product (mboitRcp: include mboit_math.glsl first), so that GL and
// Vulkan round alike. Measured: the lookup's depth (ndc.z of toLightNdc) was
// up to 2.4e-7 apart between the backends, with this it is bit for bit equal.
// The light pass reads it from the interpolated world position, which agrees
// between the APIs since the vertex shaders compute their clip positions with
// toViewClip (MomentShadowsParity's note in tests/test_moments.cpp).

// The light's window depth of a world position.
float msmLightDepth(vec3 worldPos) {
  precise vec4 c = clipOf(msmViewProj, worldPos);
  precise float z = c.z * mboitRcp(c.w);
  return z;
}

// Light window depth to [-1, 1] over the hair's depth range (linear: the
// light's depth is already what the moments should resolve).
float msmDepth(float z) {
  precise float u =
      clamp((z - msmRange.x) * mboitRcp(max(msmRange.y - msmRange.x, 1e-12)), 0.0, 1.0);
  precise float d = u * 2.0 - 1.0;
  return d;
}
