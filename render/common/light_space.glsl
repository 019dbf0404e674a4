#ifndef SB_LIGHT_SPACE_GLSL
#define SB_LIGHT_SPACE_GLSL
// Shared with C++ (light_space.h, SB_LIGHT_SPACE_CPU): lightDistance.
#ifndef SB_INLINE
#define SB_INLINE
#endif

// The depth the opacity techniques (OSM, DOM, DC, occupancy) slice and look
// up in. The papers place slices and layers by distance from the light; a
// point light's perspective window depth z = a + b / w is not linear in that
// distance (most of [0,1] is spent near the light), so for a point light
// this returns the linear depth w along the light's axis, normalized to [0,1]
// between its near and far planes. Along one light ray (one map texel) w is
// proportional to the distance from the light, and equal steps of w are the
// paper's slices perpendicular to the light direction. Directional lights
// (orthographic: the clip w row of the matrix is (0,0,0,1)) keep the window
// depth, which is already linear. The near and far planes are read from the
// matrix itself (rows z and w of a perspective projection times a rigid view:
// clip.z = a clip.w + b), so every shader that has the light's matrix can use
// it; the atlas tiling of OSM changes rows x and y only. Monotonic in z, so
// min/max of window depths map to min/max of distances. The lookups subtract
// their depth bias from the window depth before converting, so `bias` keeps
// one meaning (light window depth units) for every technique and for the
// exact reference.
SB_INLINE float lightDistance(mat4 vp, float windowZ) {
  vec3 rw = vec3(vp[0][3], vp[1][3], vp[2][3]);  // clip.w row (xyz)
  float ww = dot(rw, rw);
  if (ww == 0.0f) return windowZ;
  vec3 rz = vec3(vp[0][2], vp[1][2], vp[2][2]);
  float a = dot(rz, rw) / ww;
  float b = vp[3][2] - a * vp[3][3];
  float nearW = -b / a, farW = b / (1.0f - a);  // window z 0 and 1
  float w = b / (windowZ - a);
  return (w - nearW) / (farW - nearW);
}

#ifndef SB_LIGHT_SPACE_CPU
// m * (p, 1), the sums in one written order and `precise` (no fused
// multiply-adds): GL's GLSL compiler and glslang's SPIR-V otherwise round the
// product differently in the last bit, and the rasterizers then interpolate
// every attribute (and gl_FragCoord.z) 1-2 ulp apart between the APIs, which
// moment shadow maps amplify (MomentShadowsParity in tests/test_moments.cpp).
vec4 clipOf(mat4 m, vec3 p) {
  precise vec4 c = ((m[0] * p.x + m[1] * p.y) + m[2] * p.z) + m[3];
  return c;
}

// A point in the light's normalized device coordinates. Outside the light's
// frustum nothing the light's maps saw can occlude it: every lookup returns 1.
bool toLightNdc(mat4 lightViewProj, vec3 worldPos, out vec3 ndc) {
  vec4 clip = lightViewProj * vec4(worldPos, 1.0);
  ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) && ndc.z <= 1.0;
}
#endif
#endif
