// One map pass of osm (map.frag).
// Declared once for the C++ and the GLSL (render/common/uniform_block.h).
#ifndef SB_OSM_PASS_UNIFORMS_H
#define SB_OSM_PASS_UNIFORMS_H

#include "render/common/uniform_block.h"
#include "techniques/osm/slots.h"

// clang-format off
SB_UNIFORM_BLOCK(OsmPass, SB_SLOT_OSM_PASS)
  SB_FIELD(ivec4, osmPass)  // first texel group of target 0, first map, end map, 0
  SB_FIELD(vec4, osmTile)   // the tile's pixel rectangle x0, y0, x1, y1
SB_UNIFORM_BLOCK_END(OsmPass)
// clang-format on

#endif  // SB_OSM_PASS_UNIFORMS_H
