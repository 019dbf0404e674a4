// Bindings of the exact shadow technique (8..15, the shadow range).
#include "render/common/slots.h"
#include "uniforms.h"
// Counts: fragments per texel; offsets: their prefix sum; cursor: fill / layers
// peeled; nodes: sorted keys per texel (nodes.glsl); state: peeling state.
layout(std430, binding = SB_SLOT_EXACT_COUNTS) buffer ExactCounts { uint exactCounts[]; };
layout(std430, binding = SB_SLOT_EXACT_OFFSETS) buffer ExactOffsets { uint exactOffsets[]; };
layout(std430, binding = SB_SLOT_EXACT_CURSOR) buffer ExactCursor { uint exactCursor[]; };
layout(std430, binding = SB_SLOT_EXACT_STATE) buffer ExactState { uvec4 exactState[]; };
layout(std430, binding = SB_SLOT_EXACT_STATUS) buffer ExactStatus { uint exactOverflow; };
#include "nodes.glsl"
