// dc: the lookup (params, range, counts, sums, squares) and the cluster passes
// Its own binding names, for its C++ (#include "techniques/dc/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_DC_SLOTS_H
#define SB_DC_SLOTS_H

#define SB_SLOT_DC_PARAMS 8
#define SB_SLOT_DC_RANGE 9
#define SB_SLOT_DC_COUNTS 10
#define SB_SLOT_DC_SUMS 11
#define SB_SLOT_DC_SQUARES 12
#define SB_SLOT_DC_CENTRES 13

#endif  // SB_DC_SLOTS_H
