// Light-space depth peeling, one step (SB_PEEL_PASS 0 or 1, see peel_step.glsl).
#include "render/common/view.glsl"
#include "render/common/fragment_key.glsl"
#include "exact.glsl"
#define peelState exactState
#define peeled exactCursor
#include "render/common/peel_step.glsl"

void main() { peelStep(pixelIndex(exactParams.y), fragmentKey()); }
