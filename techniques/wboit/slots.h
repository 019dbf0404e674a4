// wboit: the resolve samples target i at SB_SLOT_BLENDED_TARGETS + i
// (render/common/slots.h)
// Its own binding names, for its C++ (#include "techniques/wboit/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_WBOIT_SLOTS_H
#define SB_WBOIT_SLOTS_H

#define SB_SLOT_WBOIT_ACCUM 16      // target 0
#define SB_SLOT_WBOIT_REVEALAGE 17  // target 1

#endif  // SB_WBOIT_SLOTS_H
