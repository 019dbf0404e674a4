#pragma once

#include <memory>

#include "backends/driver.h"

namespace sb {
// GL 4.5 core over EGL surfaceless (platform "egl") or OSMesa ("osmesa").
std::unique_ptr<Driver> createGLDriver(const DeviceOptions& opts);
}  // namespace sb
