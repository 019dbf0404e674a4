// weighted: the resolve samples target i at SB_SLOT_BLENDED_TARGETS + i
// (render/common/slots.h)
// Its own binding names, for its C++ (#include "techniques/weighted/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_WEIGHTED_SLOTS_H
#define SB_WEIGHTED_SLOTS_H

#define SB_SLOT_WEIGHTED_ACCUM 16   // target 0
#define SB_SLOT_WEIGHTED_COUNT 17   // target 1

#endif  // SB_WEIGHTED_SLOTS_H
