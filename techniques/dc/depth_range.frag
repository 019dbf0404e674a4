// Nearest and furthest hair fragment of each light texel (the range the
// initial cluster centres are spread over): min blending of (z, -z), RG32F.
layout(location = 0) out vec4 outRange;

void main() { outRange = vec4(gl_FragCoord.z, -gl_FragCoord.z, 0.0, 0.0); }
