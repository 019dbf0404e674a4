// peel_classic: the layer pass (beside the shadow lookup), then the blend and
// composite (full-screen passes)
// Its own binding names, for its C++ (#include "techniques/peel_classic/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_PEEL_CLASSIC_SLOTS_H
#define SB_PEEL_CLASSIC_SLOTS_H

#define SB_SLOT_PEELC_PREV_DEPTH 16
#define SB_SLOT_PEELC_OPAQUE_DEPTH 17
#define SB_SLOT_PEELC_LAYER_COLOR 16
#define SB_SLOT_PEELC_LAYER_DEPTH 17
#define SB_SLOT_PEELC_UNDER 16

#endif  // SB_PEEL_CLASSIC_SLOTS_H
