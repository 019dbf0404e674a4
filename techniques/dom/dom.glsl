// Parameters of deep opacity maps (binding 8), for the passes and the lookup.
#include "slots.h"
#include "uniforms.h"
#define SB_LAYER_BOUND(k) domD[(k) / 4][(k) % 4]
