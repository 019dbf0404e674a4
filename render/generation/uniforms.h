// The generation pass's parameters, declared once for the C++ and the GLSL
// (render/common/uniform_block.h): the groom's sizes and the rule's scalars
// (scenes/groom.h).
#ifndef SB_GENERATION_UNIFORMS_H
#define SB_GENERATION_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "render/generation/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(GenerationParams, SB_SLOT_GEN_PARAMS)
  SB_FIELD(uvec4, genSizes)  // guides, points per strand, strands per instance, instances
  SB_FIELD(vec4, genRule)    // spread, offset, noise, clump (world units where lengths)
  SB_FIELD(vec4, genMore)    // along step (1 / (points - 1)), scene opacity, 0, 0
  SB_FIELD(uvec4, genTotal)  // points in all (the kept strands'), 0, 0, 0
SB_UNIFORM_BLOCK_END(GenerationParams)
// clang-format on

#endif  // SB_GENERATION_UNIFORMS_H
