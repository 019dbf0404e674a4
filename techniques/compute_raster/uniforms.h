// The parameters of every compute_raster pass, declared once for the C++ and
// the GLSL (render/common/uniform_block.h).
#ifndef SB_COMPUTE_RASTER_UNIFORMS_H
#define SB_COMPUTE_RASTER_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/compute_raster/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(CRasterParams, SB_SLOT_CRASTER_PARAMS)
  SB_FIELD(uvec4, crTiles)   // tiles across, tiles down, tile size, tile count
  SB_FIELD(vec4, crStrand)   // width (pixels), 0, 0, early-termination transmittance
  SB_FIELD(uvec4, crSize)    // frame width, height (pixels), 0, 0
  SB_FIELD(uvec4, crModel)   // coverage (0 analytic, 1 binary), lines (1) or ribbons (0), segments, width from thickness (1)
  SB_FIELD(vec4, crWidth)    // width=thickness: pixels per world unit at clip w = 1, 0, 0, 0
SB_UNIFORM_BLOCK_END(CRasterParams)
// clang-format on

#endif  // SB_COMPUTE_RASTER_UNIFORMS_H
