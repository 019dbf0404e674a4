// The viewer's overlay over the image it shows (cli/view_overlay.cpp): the text
// image (RGBA8, straight alpha: a translucent box, opaque glyphs) mixed over the
// image clamped to [0,1] as present() would show it, so that where the text is
// transparent the window shows exactly the image.
#include "slots.h"

layout(binding = SB_SLOT_OVERLAY_IMAGE) uniform sampler2D shownImage;
layout(binding = SB_SLOT_OVERLAY_TEXT) uniform sampler2D overlayText;
layout(location = 0) out vec4 outColor;

void main() {
  const ivec2 p = ivec2(gl_FragCoord.xy);
  const vec4 image = texelFetch(shownImage, p, 0);
  const vec4 text = texelFetch(overlayText, p, 0);
  outColor = text.a == 0.0 ? image : vec4(mix(clamp(image.rgb, 0.0, 1.0), text.rgb, text.a), 1.0);
}
