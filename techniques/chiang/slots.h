// chiang: its table in the hair shading passes (shading.glsl)
// Its own binding names, for its C++ (#include "techniques/chiang/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_CHIANG_SLOTS_H
#define SB_CHIANG_SLOTS_H

// Past the model's uniform block (SB_SLOT_SHADING_MODEL): the h-averaged lobes (chiang.glsl).
#define SB_SLOT_CHIANG_TABLE 27

#endif  // SB_CHIANG_SLOTS_H
