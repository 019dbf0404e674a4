// The light's visibility at the nearest surface of each pixel, as the shadow
// technique reconstructs it: compared with the exact one, it judges the
// shadow technique without shading noise. Background pixels stay -1.
#include <shadow>

layout(location = 0) in vec3 vWorldPos;
layout(location = 0) out vec4 outVisibility;

void main() { outVisibility = vec4(shadowVisibility(vWorldPos), 0.0, 0.0, 1.0); }
