// probe: the points and their shadow values (beside the shadow lookup)
// Its own binding names, for its C++ (#include "render/outputs/probe/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_PROBE_SLOTS_H
#define SB_PROBE_SLOTS_H

#define SB_SLOT_PROBE_POINTS 16
#define SB_SLOT_PROBE_VALUES 17

#endif  // SB_PROBE_SLOTS_H
