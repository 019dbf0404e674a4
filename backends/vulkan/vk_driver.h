// The Vulkan driver: Vulkan 1.3 headless (VulkanPlatform), dynamic rendering,
// one graphics+compute queue, GLSL compiled at run time by glslang.
#pragma once

#include <memory>

#include "backends/driver.h"

namespace sb {
// Throws DeviceError ("no Vulkan device found ...") when no usable device exists.
std::unique_ptr<Driver> createVulkanDriver(const DeviceOptions& opts);
}  // namespace sb
