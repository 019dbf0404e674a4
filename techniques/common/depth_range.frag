// Depth-range map: the nearest and furthest hair fragment of each light texel
// in one pass, min blending of (z, -z) into an RG32F target (occupancy maps;
// density clustering spreads its initial cluster centres over this range).
layout(location = 0) out vec4 outRange;

void main() { outRange = vec4(gl_FragCoord.z, -gl_FragCoord.z, 0.0, 0.0); }
