// Bindings of shortcut (SB_SHORTCUT_K depths and colours per pixel).
#include "slots.h"
layout(std430, binding = SB_SLOT_SHORTCUT_DEPTHS) buffer ShortcutDepths { uint scDepths[]; };
layout(std430, binding = SB_SLOT_SHORTCUT_COLORS) buffer ShortcutColors { vec4 scColors[]; };
layout(std430, binding = SB_SLOT_SHORTCUT_CLAIMS) buffer ShortcutClaims { uint scClaims[]; };
