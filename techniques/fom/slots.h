// fom: parameters (passes and lookup), the coefficients (lookup)
// Its own binding names, for its C++ (#include "techniques/fom/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_FOM_SLOTS_H
#define SB_FOM_SLOTS_H

#define SB_SLOT_FOM_PARAMS 8
#define SB_SLOT_FOM_MAPS 9

#endif  // SB_FOM_SLOTS_H
