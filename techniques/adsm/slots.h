// adsm: the lookup (params, the hair's front depth)
// Its own binding names, for its C++ (#include "techniques/adsm/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_ADSM_SLOTS_H
#define SB_ADSM_SLOTS_H

#define SB_SLOT_ADSM_PARAMS 8
#define SB_SLOT_ADSM_DEPTH 9

#endif  // SB_ADSM_SLOTS_H
