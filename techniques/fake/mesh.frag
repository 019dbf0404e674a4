// The opaque mesh in a subset image: depth only, colour (0, 0, 0, 0) so the
// blend sees no hair there.
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(0.0); }
