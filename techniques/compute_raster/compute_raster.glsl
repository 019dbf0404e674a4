// What the compute_raster passes share: the parameters, the tiles' lists and
// the status words (compute_raster.h says what each holds).
#include "render/common/slots.h"
#include "slots.h"
#include "uniforms.h"

// The status words at the head of the cursor buffer (C++: CRasterStatus).
#define SB_CR_GENERATED 0u   // fragments with coverage, in front of the opaque depth
#define SB_CR_DROPPED 1u     // fragments past their tile's capacity (overflow)
#define SB_CR_OVERFLOWED 2u  // tiles that overflowed
#define SB_CR_MAX_TILE 3u    // the most fragments one tile was given
#define SB_CR_SEGMENTS 4u    // segments rasterized
#define SB_CR_TERMINATED 5u  // pixels whose walk stopped early (opaque enough)
#define SB_CR_STATUS_WORDS 8u

layout(std430, binding = SB_SLOT_CRASTER_CURSOR) coherent buffer Cursor { uint cursor[]; };
#ifndef SB_CRASTER_COUNT  // the counting pass binds only the cursors
layout(std430, binding = SB_SLOT_CRASTER_LAYOUT) readonly buffer Layout { uvec2 tileLayout[]; };
layout(std430, binding = SB_SLOT_CRASTER_FRAGMENTS) coherent buffer Fragments {
  uvec4 fragments[];  // depth bits, segment, t bits, (pixel in tile << 16) | coverage (unorm16)
};
#endif
