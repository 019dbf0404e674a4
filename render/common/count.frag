// Counts the fragments of every pixel (depth complexity; list sizes).
// COUNTS_BINDING: the storage buffer of per-pixel counts.
// Storage writes are side effects: without early tests they would happen even
// for fragments the opaque depth test then rejects.
layout(early_fragment_tests) in;
#include "view.glsl"
#include "fragment_key.glsl"

layout(std430, binding = COUNTS_BINDING) buffer Counts { uint counts[]; };

void main() { atomicAdd(counts[pixelIndex(viewViewport.x)], 1u); }
