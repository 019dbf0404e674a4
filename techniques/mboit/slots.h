// mboit: the parameters (both hair passes), the moment targets sampled by the
// second hair pass and the accumulation sampled by the resolve
// Its own binding names, for its C++ (#include "techniques/mboit/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_MBOIT_SLOTS_H
#define SB_MBOIT_SLOTS_H

#define SB_SLOT_MBOIT_PARAMS 16
#define SB_SLOT_MBOIT_B0 17
#define SB_SLOT_MBOIT_LOW 18
#define SB_SLOT_MBOIT_HIGH 19
#define SB_SLOT_MBOIT_ACCUM 20

#endif  // SB_MBOIT_SLOTS_H
