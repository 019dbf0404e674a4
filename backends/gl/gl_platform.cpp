// The nesting of GL contexts on a thread (gl_platform.h).
#include "backends/gl/gl_platform.h"

#include <algorithm>
#include <vector>

namespace sb {
namespace {
// This thread's live platforms, oldest first.
thread_local std::vector<GLPlatform*> live;
}  // namespace

void GLPlatform::entered() { live.push_back(this); }

void GLPlatform::left() {
  const auto at = std::find(live.begin(), live.end(), this);
  if (at == live.end()) return;
  live.erase(at);
  if (!live.empty()) live.back()->makeCurrent();
}

}  // namespace sb
