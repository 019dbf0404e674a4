// No self-shadowing: no passes, visibility 1 everywhere.
#include "techniques/none/none.h"

namespace sb {}  // namespace sb
