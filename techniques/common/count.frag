// Counts the fragments of every pixel (depth complexity; list sizes).
// COUNTS_BINDING: the storage buffer of per-pixel counts.
#include "view.glsl"
#include "fragment_key.glsl"

layout(std430, binding = COUNTS_BINDING) buffer Counts { uint counts[]; };

void main() { atomicAdd(counts[pixelIndex(viewViewport.x)], 1u); }
