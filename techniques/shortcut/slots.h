// shortcut: the k nearest depths, their colours and claims, the tail targets
// Its own binding names, for its C++ (#include "techniques/shortcut/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_SHORTCUT_SLOTS_H
#define SB_SHORTCUT_SLOTS_H

#define SB_SLOT_SHORTCUT_PARAMS 16
#define SB_SLOT_SHORTCUT_DEPTHS 18
#define SB_SLOT_SHORTCUT_COLORS 19
#define SB_SLOT_SHORTCUT_CLAIMS 20
#define SB_SLOT_SHORTCUT_TAIL 21
#define SB_SLOT_SHORTCUT_REVEALAGE 22

#endif  // SB_SHORTCUT_SLOTS_H
