// msm: parameters (light pass and lookup), b0 and the moment targets (lookup)
// Its own binding names, for its C++ (#include "techniques/msm/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_MSM_SLOTS_H
#define SB_MSM_SLOTS_H

#define SB_SLOT_MSM_PARAMS 8
#define SB_SLOT_MSM_B0 9
#define SB_SLOT_MSM_LOW 10
#define SB_SLOT_MSM_HIGH 11

#endif  // SB_MSM_SLOTS_H
