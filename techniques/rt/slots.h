// rt: parameters, BVH nodes, segments (in BVH order), status (rays capped),
// the acceleration structure of the segments' boxes (the ray-query tier)
// Its own binding names, for its C++ (#include "techniques/rt/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_RT_SLOTS_H
#define SB_RT_SLOTS_H

#define SB_SLOT_RT_PARAMS 8
#define SB_SLOT_RT_NODES 9
#define SB_SLOT_RT_SEGMENTS 10
#define SB_SLOT_RT_STATUS 11
#define SB_SLOT_RT_SCENE 12

#endif  // SB_RT_SLOTS_H
