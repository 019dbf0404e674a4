// kajiya-kay's parameters in the hair shading passes (its shading.glsl).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_KAJIYA_KAY_UNIFORMS_H
#define SB_KAJIYA_KAY_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(KajiyaKayParams, SB_SLOT_SHADING_MODEL)
  SB_FIELD(float, kajiyaKayDiffuse)
  SB_FIELD(float, kajiyaKaySpecular)
  SB_FIELD(float, kajiyaKayShininess)
  SB_FIELD(float, kajiyaKayUnused)  // std140 rounds the block to 16 bytes
SB_UNIFORM_BLOCK_END(KajiyaKayParams)
// clang-format on

#endif  // SB_KAJIYA_KAY_UNIFORMS_H
