// fake: the three subset images in the blend (a full-screen pass)
// Its own binding names, for its C++ (#include "techniques/fake/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_FAKE_SLOTS_H
#define SB_FAKE_SLOTS_H

#define SB_SLOT_FAKE_IMAGE0 16
#define SB_SLOT_FAKE_IMAGE1 17
#define SB_SLOT_FAKE_IMAGE2 18

#endif  // SB_FAKE_SLOTS_H
