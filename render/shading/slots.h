// shading: the shading model's table in the hair shading passes (chiang's lobes)
// Its own binding names, for its C++ (#include "render/shading/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_SHADING_SLOTS_H
#define SB_SHADING_SLOTS_H

// Past the transparency techniques' range: the hair shading passes bind theirs too.
#define SB_SLOT_SHADING_TABLE 26

#endif  // SB_SHADING_SLOTS_H
