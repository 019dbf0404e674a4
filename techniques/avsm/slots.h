// avsm: the lookup (params, nodes per texel, the nodes); the resolve pass
// (compute) reads exact's lists at the EXACT slots (render/common/slots.h)
// and writes at 0..3
// Its own binding names, for its C++ (#include "techniques/avsm/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_AVSM_SLOTS_H
#define SB_AVSM_SLOTS_H

#define SB_SLOT_AVSM_PARAMS 8
#define SB_SLOT_AVSM_COUNT 9
#define SB_SLOT_AVSM_NODES 10
#define SB_SLOT_AVSM_OUT_COUNT 0
#define SB_SLOT_AVSM_OUT_NODES 1
#define SB_SLOT_AVSM_OUT_STATUS 2
#define SB_SLOT_AVSM_RESOLVE 3

#endif  // SB_AVSM_SLOTS_H
