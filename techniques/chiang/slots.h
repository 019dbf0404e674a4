// chiang: the table of azimuthal lobes the shading passes read (beside every technique's own)
// Its own binding names, for its C++ (#include "techniques/chiang/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// techniques/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_CHIANG_SLOTS_H
#define SB_CHIANG_SLOTS_H

#define SB_SLOT_CHIANG_TABLE 26

#endif  // SB_CHIANG_SLOTS_H
