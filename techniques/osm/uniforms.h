// osm's parameters (its map passes and lookup).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_OSM_UNIFORMS_H
#define SB_OSM_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/osm/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(OsmParams, SB_SLOT_OSM_PARAMS)
  SB_FIELD(mat4, osmViewProj)
  SB_FIELD(vec4, osmParams)   // bias (light depth units), map size, shadow alpha, weight
                              // per fragment
  SB_FIELD(ivec4, osmLayout)  // tile columns, maps, atlases, filter (opacity_filter.glsl)
  // D_0..D_n, 4 per vec4: n <= 512 (the OSM paper's Plate 3 uses 500 maps)
  SB_ARRAY(vec4, osmSlices, 129)
SB_UNIFORM_BLOCK_END(OsmParams)
// clang-format on

#endif  // SB_OSM_UNIFORMS_H
