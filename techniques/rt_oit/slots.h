// rt (transparency): its own binding names, for its C++ (#include
// "techniques/rt_oit/slots.h") and its GLSL (#include "slots.h"); the ranges
// and the shared names (the accumulation, 16) are in render/common/slots.h.
#ifndef SB_RT_OIT_SLOTS_H
#define SB_RT_OIT_SLOTS_H

#define SB_SLOT_RT_OIT_PARAMS 18    // RtOitParams
#define SB_SLOT_RT_OIT_NODES 19     // the software tier: the eye BVH's nodes (techniques/rt/bvh.h)
#define SB_SLOT_RT_OIT_SEGMENTS 20  // the segments in BVH (or scene) order: (a, radius), (b, index)
#define SB_SLOT_RT_OIT_STATUS 21    // uint counters: hits, pixels capped, pixels merged
#define SB_SLOT_RT_OIT_OPAQUE 22    // the opaque depth (when a mesh was drawn)
#define SB_SLOT_RT_OIT_SCENE 23  // the ray-query tier: the segments' boxes' acceleration structure

#endif  // SB_RT_OIT_SLOTS_H
