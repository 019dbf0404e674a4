// The three subset images blended with equal weights: writes (sum c a / 3,
// 1 - sum a / 3), blended One, SrcAlpha over the opaque colour (fake.h).
#include "slots.h"

layout(binding = SB_SLOT_FAKE_IMAGE0) uniform sampler2D fakeImage0;
layout(binding = SB_SLOT_FAKE_IMAGE1) uniform sampler2D fakeImage1;
layout(binding = SB_SLOT_FAKE_IMAGE2) uniform sampler2D fakeImage2;
layout(location = 0) out vec4 outColor;

void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(fakeImage0, p, 0), b = texelFetch(fakeImage1, p, 0),
       c = texelFetch(fakeImage2, p, 0);
  // Premultiplied: alpha 1 where hair was drawn, (0, 0, 0, 0) elsewhere, and
  // with --msaa the averages of the samples (fake.cpp).
  vec3 hair = (a.rgb + b.rgb + c.rgb) / 3.0;
  float coverage = (a.a + b.a + c.a) / 3.0;
  outColor = vec4(hair, 1.0 - coverage);
}
