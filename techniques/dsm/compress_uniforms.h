// dsm's compression parameters (compress.comp, through dsm.glsl).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_DSM_COMPRESS_UNIFORMS_H
#define SB_DSM_COMPRESS_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/dsm/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(DsmCompressParams, SB_SLOT_DSM_COMPRESS)
  // x: epsilon, y: transmittance 1 - alpha_s, z: map size, w: max nodes
  SB_FIELD(vec4, dsmCompress)
SB_UNIFORM_BLOCK_END(DsmCompressParams)
// clang-format on

#endif  // SB_DSM_COMPRESS_UNIFORMS_H
