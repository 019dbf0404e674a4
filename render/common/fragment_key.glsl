// Every hair fragment of a pixel (or light texel) gets a unique order key:
// (window depth bits, primitive id). Non-negative floats order like their
// bits, and one primitive covers a pixel at most once, so depth peeling and
// sorted fragment lists break ties in depth the same way. Fragment stage only.
#include "key_order.glsl"

uvec2 fragmentKey() { return uvec2(floatBitsToUint(gl_FragCoord.z), uint(gl_PrimitiveID)); }

// Row-major index of this fragment's pixel in a target `width` pixels wide.
uint pixelIndex(float width) { return uint(gl_FragCoord.y) * uint(width) + uint(gl_FragCoord.x); }
