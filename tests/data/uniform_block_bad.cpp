// Must not compile: a float then a vec2 is not std140 in C++ (glm aligns the
// vec2 to 4, std140 to 8), and SB_UNIFORM_BLOCK_END's static_assert says so.
// Compiled by the UniformBlockStd140CheckFails test (CMakeLists.txt), which
// expects the assert's message; with -DSB_GOOD it compiles (the control).
#include "render/common/uniform_block.h"

// clang-format off
SB_UNIFORM_BLOCK(BadBlock, 0)
#ifdef SB_GOOD
  SB_FIELD(vec2, b)
  SB_FIELD(float, a)
  SB_FIELD(float, c)
#else
  SB_FIELD(float, a)
  SB_FIELD(vec2, b)
#endif
SB_UNIFORM_BLOCK_END(BadBlock)
// clang-format on

int main() { return 0; }
