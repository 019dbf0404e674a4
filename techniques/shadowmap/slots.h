// shadowmap: the lookup (the depth map, its parameters)
// Its own binding names, for its C++ (#include "techniques/shadowmap/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_SHADOWMAP_SLOTS_H
#define SB_SHADOWMAP_SLOTS_H

#define SB_SLOT_SHADOWMAP_DEPTH 8
#define SB_SLOT_SHADOWMAP_PARAMS 9

#endif  // SB_SHADOWMAP_SLOTS_H
