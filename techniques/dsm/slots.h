// dsm: the lookup (params, nodes kept per texel, their offsets, the nodes);
// the compression pass (compute) reads exact's sorted lists at the EXACT slots
// (render/common/slots.h) and writes the nodes at 0..3 (no geometry bound there)
// Its own binding names, for its C++ (#include "techniques/dsm/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_DSM_SLOTS_H
#define SB_DSM_SLOTS_H

#define SB_SLOT_DSM_PARAMS 8
#define SB_SLOT_DSM_KEPT 9
#define SB_SLOT_DSM_OFFSETS 10
#define SB_SLOT_DSM_NODES 11
#define SB_SLOT_DSM_OUT_KEPT 0
#define SB_SLOT_DSM_OUT_OFFSETS 1
#define SB_SLOT_DSM_OUT_NODES 2
#define SB_SLOT_DSM_OUT_STATUS 3
#define SB_SLOT_DSM_COMPRESS 4

#endif  // SB_DSM_SLOTS_H
