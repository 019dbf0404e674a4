// occupancy_oit: the maps in the accumulation (beside the shadow lookup), and
// the resolve's inputs (a full-screen pass)
// Its own binding names, for its C++ (#include "techniques/occupancy_oit/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_OCCUPANCY_OIT_SLOTS_H
#define SB_OCCUPANCY_OIT_SLOTS_H

#define SB_SLOT_OOIT_RANGE 20
#define SB_SLOT_OOIT_BITS 21
#define SB_SLOT_OOIT_SLABS 25
#define SB_SLOT_OOIT_ACCUM 0
#define SB_SLOT_OOIT_LOG2T 1

#endif  // SB_OCCUPANCY_OIT_SLOTS_H
