// Parameters of Fourier opacity maps, for the accumulation passes and the lookup.
#include "slots.h"
#include "uniforms.h"
// Normalised depth d in [0, 1] over the hair's depth range.
float fomDepth(float z) { return (z - fomRange.x) / max(fomRange.y - fomRange.x, 1e-12); }
