// What `render` prints without --json: a summary a person reads (times to three
// significant digits, the errors and depth complexity as words), not the JSON.
#pragma once

#include <ostream>

#include "harness/render.h"

namespace sb {

void printRenderSummary(std::ostream& out, const RenderRequest& req, const RenderResult& r);

}  // namespace sb
