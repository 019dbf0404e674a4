// A point in the light's normalized device coordinates. Outside the light's
// frustum nothing the light's maps saw can occlude it: every lookup returns 1.
bool toLightNdc(mat4 lightViewProj, vec3 worldPos, out vec3 ndc) {
  vec4 clip = lightViewProj * vec4(worldPos, 1.0);
  ndc = clip.xyz / clip.w;
  vec2 uv = ndc.xy * 0.5 + 0.5;
  return all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0))) && ndc.z <= 1.0;
}
