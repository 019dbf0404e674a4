// Stochastic transparency, total alpha: every visible hair fragment multiplies
// the R32F target by (1 - a) (blend Zero, OneMinusSrcColor): prod(1 - a), the
// exact transmittance the alpha correction scales to.
layout(location = 2) in vec4 vColor;
layout(location = 0) out vec4 outAlpha;

void main() { outAlpha = vec4(vColor.a); }
