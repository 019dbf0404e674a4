// compute_raster: its own binding names, for its C++ (#include
// "techniques/compute_raster/slots.h") and its GLSL (#include "slots.h"); the
// ranges and the shared names (the accumulation, 16) are in render/common/slots.h.
#ifndef SB_COMPUTE_RASTER_SLOTS_H
#define SB_COMPUTE_RASTER_SLOTS_H

#define SB_SLOT_CRASTER_CURSOR 18     // uint: 8 status words, then each tile's cursor
#define SB_SLOT_CRASTER_LAYOUT 19     // uvec2 per tile: first entry in the pool, capacity
#define SB_SLOT_CRASTER_FRAGMENTS 20  // uvec4 per fragment: depth, segment, t, pixel|coverage
#define SB_SLOT_CRASTER_SHADED 21     // vec4 per segment end: shaded rgb, alpha (shading=point)
#define SB_SLOT_CRASTER_OPAQUE 22     // the opaque depth (when a mesh was drawn)
#define SB_SLOT_CRASTER_PARAMS 23     // CRasterParams
#define SB_SLOT_CRASTER_BUCKETS 24    // each tile's list bucketed by pixel (the bucket pass's copy)
#define SB_SLOT_CRASTER_RANGES 25     // uvec2 per pixel: its first entry in the buckets, its count

#endif  // SB_COMPUTE_RASTER_SLOTS_H
