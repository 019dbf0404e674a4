// No self-shadowing: no passes, visibility 1 everywhere.
#include "techniques/none/none.h"

namespace sb {

std::string NoShadow::lookupShader() const { return "techniques/none/lookup.glsl"; }

}  // namespace sb
