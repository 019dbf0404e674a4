// dual_peel: the peel pass (beside the shadow lookup), then the back blend and
// the final (full-screen passes)
// Its own binding names, for its C++ (#include "techniques/dual_peel/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_DUAL_PEEL_SLOTS_H
#define SB_DUAL_PEEL_SLOTS_H

#define SB_SLOT_DUAL_DEPTH 16
#define SB_SLOT_DUAL_FRONT 17
#define SB_SLOT_DUAL_OPAQUE_DEPTH 18
#define SB_SLOT_DUAL_BACK_TEMP 16
#define SB_SLOT_DUAL_FRONT_FINAL 16
#define SB_SLOT_DUAL_BACK_FINAL 17

#endif  // SB_DUAL_PEEL_SLOTS_H
