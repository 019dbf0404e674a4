#include "backends/vulkan/vk_window.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstring>

#include "backends/vulkan/vk_util.h"
#include "backends/window/glfw_window.h"

namespace sb {

std::vector<const char*> windowInstanceExtensions() {
  if (!glfwVulkanSupported())
    throw DeviceError("no Vulkan window: GLFW finds no Vulkan loader (" + glfwLastError() + ")");
  uint32_t n = 0;
  const char** names = glfwGetRequiredInstanceExtensions(&n);
  if (!names)
    throw DeviceError("no Vulkan window: the Vulkan driver offers no surface extension for " +
                      std::string("this window system (") + glfwLastError() + ")");
  return std::vector<const char*>(names, names + n);
}

VkSurfaceKHR createWindowSurface(VkInstance instance, GlfwWindow& window) {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  const VkResult r = glfwCreateWindowSurface(instance, window.handle(), nullptr, &surface);
  if (r != VK_SUCCESS)
    throw DeviceError(std::string("no Vulkan window: glfwCreateWindowSurface failed with ") +
                      resultName(r) + " (" + glfwLastError() + ")");
  return surface;
}

namespace {

const char* presentModeName(VkPresentModeKHR m) {
  switch (m) {
    case VK_PRESENT_MODE_IMMEDIATE_KHR:
      return "immediate";
    case VK_PRESENT_MODE_MAILBOX_KHR:
      return "mailbox";
    case VK_PRESENT_MODE_FIFO_KHR:
      return "fifo";
    case VK_PRESENT_MODE_FIFO_RELAXED_KHR:
      return "fifo_relaxed";
    default:
      return "other";
  }
}

const char* formatText(VkFormat f) {
  switch (f) {
    case VK_FORMAT_B8G8R8A8_UNORM:
      return "B8G8R8A8_UNORM";
    case VK_FORMAT_R8G8B8A8_UNORM:
      return "R8G8B8A8_UNORM";
    case VK_FORMAT_B8G8R8A8_SRGB:
      return "B8G8R8A8_SRGB";
    case VK_FORMAT_R8G8B8A8_SRGB:
      return "R8G8B8A8_SRGB";
    default:
      return "another format";
  }
}

VkImageMemoryBarrier imageBarrier(VkImage image, VkImageLayout from, VkImageLayout to,
                                  VkAccessFlags srcAccess, VkAccessFlags dstAccess) {
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = srcAccess;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  return b;
}

}  // namespace

VulkanSwapchain::VulkanSwapchain(const VulkanPlatform& platform, VulkanResources& resources)
    : platform_(platform), resources_(resources), device_(platform.device) {
  const VkPhysicalDevice pd = platform.physical;
  uint32_t n = 0;
  check(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, platform.surface, &n, nullptr),
        "vkGetPhysicalDeviceSurfacePresentModesKHR");
  std::vector<VkPresentModeKHR> modes(n);
  check(vkGetPhysicalDeviceSurfacePresentModesKHR(pd, platform.surface, &n, modes.data()),
        "vkGetPhysicalDeviceSurfacePresentModesKHR");
  auto offered = [&](VkPresentModeKHR m) {
    return std::find(modes.begin(), modes.end(), m) != modes.end();
  };
  std::string list;
  for (VkPresentModeKHR m : modes)
    list += std::string(list.empty() ? "" : ", ") + presentModeName(m);
  std::string why;
  if (offered(VK_PRESENT_MODE_IMMEDIATE_KHR)) {
    presentMode_ = VK_PRESENT_MODE_IMMEDIATE_KHR;
    why = "offered: no vsync, a present never waits for the display";
  } else if (offered(VK_PRESENT_MODE_MAILBOX_KHR)) {
    presentMode_ = VK_PRESENT_MODE_MAILBOX_KHR;
    why = "immediate not offered; mailbox does not wait for the display";
  } else {
    presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
    why = "neither immediate nor mailbox offered; fifo (vsync) is the one every device has";
  }

  check(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, platform.surface, &n, nullptr),
        "vkGetPhysicalDeviceSurfaceFormatsKHR");
  std::vector<VkSurfaceFormatKHR> formats(n);
  check(vkGetPhysicalDeviceSurfaceFormatsKHR(pd, platform.surface, &n, formats.data()),
        "vkGetPhysicalDeviceSurfaceFormatsKHR");
  if (formats.empty()) throw DeviceError("no Vulkan window: the surface offers no format");
  // UNORM, not sRGB: the window shows the values a PNG of the image holds.
  format_ = formats.front();
  for (const auto& f : formats)
    if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
        f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
      format_ = f;
      break;
    }
  mode_ = std::string("GLFW window, swapchain ") + formatText(format_.format) +
          ", blit and present, present mode " + presentModeName(presentMode_) + " (" + why +
          "; modes offered: " + list + ")";

  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  check(vkCreateSemaphore(device_, &si, nullptr, &acquired_), "vkCreateSemaphore");
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  check(vkCreateFence(device_, &fi, nullptr, &fence_), "vkCreateFence");
  cmd_ = resources_.allocateCommandBuffer();
  ensureCurrent();
}

VulkanSwapchain::~VulkanSwapchain() {
  vkDeviceWaitIdle(device_);
  destroySwapchain(swapchain_);
  for (VkSemaphore s : copied_) vkDestroySemaphore(device_, s, nullptr);
  if (acquired_) vkDestroySemaphore(device_, acquired_, nullptr);
  if (fence_) vkDestroyFence(device_, fence_, nullptr);
}

void VulkanSwapchain::destroySwapchain(VkSwapchainKHR chain) {
  if (chain != VK_NULL_HANDLE) vkDestroySwapchainKHR(device_, chain, nullptr);
}

void VulkanSwapchain::create() {
  VkSurfaceCapabilitiesKHR caps{};
  check(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(platform_.physical, platform_.surface, &caps),
        "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == 0xFFFFFFFFu) {  // the surface takes the swapchain's size
    extent.width =
        std::clamp(platform_.window->width(), caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(platform_.window->height(), caps.minImageExtent.height,
                               caps.maxImageExtent.height);
  }
  vkDeviceWaitIdle(device_);  // the old images may still be read by a present
  for (VkSemaphore s : copied_) vkDestroySemaphore(device_, s, nullptr);
  copied_.clear();
  images_.clear();
  const VkSwapchainKHR old = swapchain_;
  swapchain_ = VK_NULL_HANDLE;
  extent_ = extent;
  outdated_ = false;
  if (extent.width == 0 || extent.height == 0) {  // minimized: no swapchain until restored
    destroySwapchain(old);
    return;
  }
  uint32_t count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
  canReadBack_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = platform_.surface;
  ci.minImageCount = count;
  ci.imageFormat = format_.format;
  ci.imageColorSpace = format_.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage =
      VK_IMAGE_USAGE_TRANSFER_DST_BIT | (canReadBack_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  if (!(caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR))
    for (uint32_t bit = 1; bit <= VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR; bit <<= 1)
      if (caps.supportedCompositeAlpha & bit) {
        ci.compositeAlpha = static_cast<VkCompositeAlphaFlagBitsKHR>(bit);
        break;
      }
  ci.presentMode = presentMode_;
  ci.clipped = VK_TRUE;
  ci.oldSwapchain = old;
  const VkResult r = vkCreateSwapchainKHR(device_, &ci, nullptr, &swapchain_);
  destroySwapchain(old);
  check(r, "vkCreateSwapchainKHR");
  uint32_t n = 0;
  check(vkGetSwapchainImagesKHR(device_, swapchain_, &n, nullptr), "vkGetSwapchainImagesKHR");
  images_.resize(n);
  check(vkGetSwapchainImagesKHR(device_, swapchain_, &n, images_.data()),
        "vkGetSwapchainImagesKHR");
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  copied_.resize(n, VK_NULL_HANDLE);
  for (VkSemaphore& s : copied_)
    check(vkCreateSemaphore(device_, &si, nullptr, &s), "vkCreateSemaphore");
}

bool VulkanSwapchain::ensureCurrent() {
  const uint32_t w = platform_.window->width(), h = platform_.window->height();
  if (w == 0 || h == 0) return false;  // minimized: keep the swapchain for the restore
  if (outdated_ || swapchain_ == VK_NULL_HANDLE || w != extent_.width || h != extent_.height)
    create();
  return swapchain_ != VK_NULL_HANDLE;
}

bool VulkanSwapchain::present(TextureRes& texture, PresentedImage* capture) {
  if (!ensureCurrent()) return false;
  uint32_t index = 0;
  VkResult r =
      vkAcquireNextImageKHR(device_, swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  if (r == VK_ERROR_OUT_OF_DATE_KHR) {  // resized between the check and the acquire
    outdated_ = true;
    if (!ensureCurrent()) return false;
    r = vkAcquireNextImageKHR(device_, swapchain_, UINT64_MAX, acquired_, VK_NULL_HANDLE, &index);
  }
  if (r == VK_SUBOPTIMAL_KHR)
    outdated_ = true;  // still presentable; remade at the next present
  else
    check(r, "vkAcquireNextImageKHR");
  const VkImage image = images_[index];
  const bool readBack = capture != nullptr && canReadBack_;
  const VkDeviceSize bytes = VkDeviceSize{extent_.width} * extent_.height * 4;
  HostBuffer staging{};
  if (readBack) staging = resources_.createHostBuffer(bytes);

  try {
    resetAndBegin(cmd_);
    std::vector<VkImageMemoryBarrier> barriers;
    transition(barriers, texture, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    barriers.push_back(imageBarrier(image, VK_IMAGE_LAYOUT_UNDEFINED,
                                    VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 0,
                                    VK_ACCESS_TRANSFER_WRITE_BIT));
    fullBarrier(cmd_, barriers);
    // Texture row 0 is the image's bottom row; swapchain row 0 is the window's top.
    VkImageBlit blit{};
    blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.srcOffsets[1] = {int32_t(texture.desc.width), int32_t(texture.desc.height), 1};
    blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    blit.dstOffsets[0] = {0, int32_t(extent_.height), 0};
    blit.dstOffsets[1] = {int32_t(extent_.width), 0, 1};
    vkCmdBlitImage(cmd_, texture.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, image,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
    VkImageLayout layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    if (readBack) {
      const VkImageMemoryBarrier toSrc =
          imageBarrier(image, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                       VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT);
      vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                           0, nullptr, 0, nullptr, 1, &toSrc);
      layout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
      VkBufferImageCopy region{};
      region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      region.imageExtent = {extent_.width, extent_.height, 1};
      vkCmdCopyImageToBuffer(cmd_, image, layout, staging.buffer, 1, &region);
      hostReadBarrier(cmd_);
    }
    const VkImageMemoryBarrier toPresent =
        imageBarrier(image, layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                     VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT, 0);
    vkCmdPipelineBarrier(cmd_, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT,
                         0, 0, nullptr, 0, nullptr, 1, &toPresent);
    check(vkEndCommandBuffer(cmd_), "vkEndCommandBuffer");

    const VkPipelineStageFlags waitStage = VK_PIPELINE_STAGE_ALL_COMMANDS_BIT;
    VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    si.waitSemaphoreCount = 1;
    si.pWaitSemaphores = &acquired_;
    si.pWaitDstStageMask = &waitStage;
    si.commandBufferCount = 1;
    si.pCommandBuffers = &cmd_;
    si.signalSemaphoreCount = 1;
    si.pSignalSemaphores = &copied_[index];
    check(vkQueueSubmit(platform_.queue, 1, &si, fence_), "vkQueueSubmit (present)");
    check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check(vkResetFences(device_, 1, &fence_), "vkResetFences");

    if (readBack) {
      capture->width = extent_.width;
      capture->height = extent_.height;
      capture->rgba8.resize(bytes);
      const auto* src = static_cast<const uint8_t*>(staging.mapped);
      const std::size_t row = std::size_t{extent_.width} * 4;
      const bool bgra =
          format_.format == VK_FORMAT_B8G8R8A8_UNORM || format_.format == VK_FORMAT_B8G8R8A8_SRGB;
      for (uint32_t y = 0; y < extent_.height; ++y) {  // bottom-up, as readTexture
        uint8_t* dst = capture->rgba8.data() + std::size_t(extent_.height - 1 - y) * row;
        std::memcpy(dst, src + std::size_t(y) * row, row);
        if (bgra)
          for (std::size_t i = 0; i < row; i += 4) std::swap(dst[i], dst[i + 2]);
      }
      resources_.destroyHostBuffer(staging);
    }
  } catch (...) {
    if (readBack) resources_.destroyHostBuffer(staging);
    throw;
  }
  if (capture && !readBack) {
    capture->width = capture->height = 0;
    capture->rgba8.clear();
  }

  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &copied_[index];
  pi.swapchainCount = 1;
  pi.pSwapchains = &swapchain_;
  pi.pImageIndices = &index;
  r = vkQueuePresentKHR(platform_.queue, &pi);
  if (r == VK_ERROR_OUT_OF_DATE_KHR || r == VK_SUBOPTIMAL_KHR)
    outdated_ = true;
  else
    check(r, "vkQueuePresentKHR");
  return true;
}

}  // namespace sb
