// Small Vulkan helpers shared by the platform, the driver and its pipelines:
// result checks and the translation of the device's enums.
#pragma once

#include <vulkan/vulkan.h>

#include "backends/device.h"

namespace sb {

const char* resultName(VkResult r);
// Throws DeviceError naming `what` and the result when r is not VK_SUCCESS.
void check(VkResult r, const char* what);
// An environment variable set to something other than "" or "0".
bool envFlag(const char* name);

VkFormat toVkFormat(Format f);
VkCompareOp toVk(CompareOp op);
VkBlendFactor toVk(BlendFactor f);
VkBlendOp toVk(BlendOp op);
VkDescriptorType toVk(BindingKind k);

}  // namespace sb
