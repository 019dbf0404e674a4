// dom: parameters (passes and lookup), the depth map z0 (opacity pass and lookup),
// the maps (lookup)
// Its own binding names, for its C++ (#include "techniques/dom/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_DOM_SLOTS_H
#define SB_DOM_SLOTS_H

#define SB_SLOT_DOM_PARAMS 8
#define SB_SLOT_DOM_DEPTH 10
#define SB_SLOT_DOM_MAPS 9

#endif  // SB_DOM_SLOTS_H
