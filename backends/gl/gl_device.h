#pragma once

#include <memory>

#include "backends/device.h"

namespace sb {
// GL 4.5 core over EGL surfaceless (platform "egl") or OSMesa ("osmesa").
std::unique_ptr<Device> createGLDevice(const DeviceOptions& opts);
}  // namespace sb
