// The occupancy paper's anti-aliasing of a light-map lookup: the lookup moves by up to half a
// texel. The offset is a smooth but fast-varying function of the point's light-space position
// in texels (a few radians per texel), deterministic and, unlike a hash of the position's
// bits, insensitive to the last-bit differences of the interpolated position between the two
// APIs. Shared so that the exact shadow can be looked up with the same jitter (the reference
// of a jittered lookup samples as it does).
vec2 lightTexelJitter(vec3 texelSpace) {
  return 0.5 * vec2(sin(dot(texelSpace, vec3(4.1414, 6.2831, 5.3792))),
                    sin(dot(texelSpace, vec3(6.9173, 3.7351, 4.7717))));
}

// The seed of jittered lookup j at a point: its texel position and its light depth in texels.
vec3 lightJitterSeed(vec2 texelPos, float ndcZ, float size, int j) {
  return vec3(texelPos, ndcZ * size + 1.618034 * float(j));
}
