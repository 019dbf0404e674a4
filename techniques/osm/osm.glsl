// Parameters of opacity shadow maps (binding 8), for the map passes and the lookup.
#include "slots.h"
#include "uniforms.h"
#define SB_LAYER_BOUND(i) osmSlices[(i) / 4][(i) % 4]
