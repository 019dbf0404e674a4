// Evaluates the shadow technique's visibility at given world positions (along
// a light ray, for the occupancy paper's Fig. 5 style plots).
#include <shadow>
#include "render/common/invocation.glsl"
#include "slots.h"
layout(local_size_x = 64) in;
layout(std430, binding = SB_SLOT_PROBE_POINTS) readonly buffer ProbePoints {
  vec4 probePoints[];  // w unused
};
layout(std430, binding = SB_SLOT_PROBE_VALUES) writeonly buffer ProbeValues {
  float probeValues[];
};

void main() {
  uint i = linearInvocation();
  if (i >= uint(probePoints.length())) return;
  probeValues[i] = shadowVisibility(probePoints[i].xyz);
}
