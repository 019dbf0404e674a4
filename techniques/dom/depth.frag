// Step 1: the depth z0 where the hair begins in each light texel, quantized
// to the depth map's bits, by min blending into the depth map and into the
// first channel of the first opacity target (cleared to 1, 0, 0, 0).
#include "dom.glsl"
#include "../common/opacity.glsl"

layout(location = 0) out vec4 domDepthOut;
layout(location = 1) out vec4 domFirstOut;

void main() {
  float z = domQuantize(gl_FragCoord.z, int(domParams.w));
  domDepthOut = vec4(z, 0.0, 0.0, 0.0);
  domFirstOut = vec4(z, 0.0, 0.0, 0.0);
}
