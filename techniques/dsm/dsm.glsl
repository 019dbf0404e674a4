// Parameters of deep shadow maps for the compression pass (compute).
#include "slots.h"
#include "compress_uniforms.h"
