// Opaque hair shaded by the chosen model (bound as <shading>); the shadow technique supplies the
// light's visibility through shadowVisibility() (bound as <shadow>).
#include "../common/shading.glsl"
#include <shadow>
#include "hair_shading.glsl"

layout(location = 0) in vec3 vWorldPos;
layout(location = 1) in vec3 vTangent;
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(shadeHair(vWorldPos, vTangent, vColor.rgb), 1.0); }
