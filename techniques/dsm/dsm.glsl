// Parameters of deep shadow maps for the compression pass (compute).
#include "slots.h"
layout(std140, binding = SB_SLOT_DSM_COMPRESS) uniform DsmCompressParams {
  vec4 dsmCompress;  // x: epsilon, y: transmittance 1 - alpha_s, z: map size, w: max nodes
};
