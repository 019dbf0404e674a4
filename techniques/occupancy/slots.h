// occupancy: the lookup; the range also in the occupancy and slab passes
// (OccupancyMaps, from the light and, for occupancy_oit, from the eye)
// Its own binding names, for its C++ (#include "techniques/occupancy/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_OCCUPANCY_SLOTS_H
#define SB_OCCUPANCY_SLOTS_H

#define SB_SLOT_OCC_PARAMS 8
#define SB_SLOT_OCC_RANGE 9
#define SB_SLOT_OCC_BITS 10
#define SB_SLOT_OCC_SLABS 11

#endif  // SB_OCCUPANCY_SLOTS_H
