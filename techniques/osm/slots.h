// osm: parameters (passes and lookup), a map pass's parameters, the atlases
// (lookup)
// Its own binding names, for its C++ (#include "techniques/osm/slots.h") and
// its GLSL (#include "slots.h"); the ranges and the shared names are in
// render/common/slots.h. Plain #defines, read by both languages.
#ifndef SB_OSM_SLOTS_H
#define SB_OSM_SLOTS_H

#define SB_SLOT_OSM_PARAMS 8
#define SB_SLOT_OSM_PASS 9
#define SB_SLOT_OSM_ATLASES 9

#endif  // SB_OSM_SLOTS_H
