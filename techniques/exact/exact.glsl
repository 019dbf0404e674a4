// Bindings of the exact shadow technique (8..15, the shadow range).
layout(std140, binding = 8) uniform ExactShadowParams {
  mat4 exactViewProj;
  vec4 exactParams;  // x: bias (light depth units), y: map size, z: shadow alpha, w: 1 = opaque map
};
layout(std430, binding = 9) buffer ExactCounts { uint exactCounts[]; };    // fragments per texel
layout(std430, binding = 10) buffer ExactOffsets { uint exactOffsets[]; };  // prefix sum of counts
layout(std430, binding = 11) buffer ExactCursor { uint exactCursor[]; };    // fill / layers peeled
layout(std430, binding = 12) buffer ExactNodes { uvec2 exactNodes[]; };     // sorted keys per texel
layout(std430, binding = 13) buffer ExactState { uvec4 exactState[]; };     // peeling state
layout(std430, binding = 14) buffer ExactStatus { uint exactOverflow; };
