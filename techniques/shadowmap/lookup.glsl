// Williams (1978) hard shadows: a point is lit when its light-space depth is
// not behind the nearest surface the light sees, up to a constant bias.
layout(binding = 8) uniform sampler2D shadowDepth;
layout(std140, binding = 9) uniform ShadowMapParams {
  mat4 shadowViewProj;
  vec4 shadowParams;  // bias (light depth units), 0, 0, 0
};

float shadowVisibility(vec3 worldPos) {
  vec4 clip = shadowViewProj * vec4(worldPos, 1.0);
  vec3 ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  // Outside the light's frustum: nothing the map saw can occlude it.
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0))) || ndc.z > 1.0) return 1.0;
  float occluder = textureLod(shadowDepth, uv, 0.0).r;
  return ndc.z - shadowParams.x > occluder ? 0.0 : 1.0;
}
