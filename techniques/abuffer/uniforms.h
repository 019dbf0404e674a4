// The size of the resolve (abuffer, and kbuffer and mlab, which reuse abuffer's C++).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_ABUFFER_UNIFORMS_H
#define SB_ABUFFER_UNIFORMS_H

#include "render/common/slots.h"
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(AbufferSize, SB_SLOT_ABUFFER_SIZE)
  SB_FIELD(uvec4, size)  // x: pixel count
SB_UNIFORM_BLOCK_END(AbufferSize)
// clang-format on

#endif  // SB_ABUFFER_UNIFORMS_H
