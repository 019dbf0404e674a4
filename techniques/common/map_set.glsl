// Up to six float maps of one shadow technique at bindings 9..14, fetched by
// an index that varies per fragment (a sampler array would need non-uniform
// indexing, which GL 4.5 lacks). Define SB_MAP_COUNT (1..6) before including.
layout(binding = 9) uniform sampler2D shadowMap0;
#if SB_MAP_COUNT > 1
layout(binding = 10) uniform sampler2D shadowMap1;
#endif
#if SB_MAP_COUNT > 2
layout(binding = 11) uniform sampler2D shadowMap2;
#endif
#if SB_MAP_COUNT > 3
layout(binding = 12) uniform sampler2D shadowMap3;
#endif
#if SB_MAP_COUNT > 4
layout(binding = 13) uniform sampler2D shadowMap4;
#endif
#if SB_MAP_COUNT > 5
layout(binding = 14) uniform sampler2D shadowMap5;
#endif

vec4 fetchShadowMap(int index, ivec2 texel) {
  vec4 v = texelFetch(shadowMap0, texel, 0);
#if SB_MAP_COUNT > 1
  if (index == 1) v = texelFetch(shadowMap1, texel, 0);
#endif
#if SB_MAP_COUNT > 2
  if (index == 2) v = texelFetch(shadowMap2, texel, 0);
#endif
#if SB_MAP_COUNT > 3
  if (index == 3) v = texelFetch(shadowMap3, texel, 0);
#endif
#if SB_MAP_COUNT > 4
  if (index == 4) v = texelFetch(shadowMap4, texel, 0);
#endif
#if SB_MAP_COUNT > 5
  if (index == 5) v = texelFetch(shadowMap5, texel, 0);
#endif
  return v;
}
