// The Vulkan window platform's pieces (`--platform window`): the instance
// extensions and surface of a GLFW window, and the swapchain that present()
// copies a texture into.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "backends/device.h"
#include "backends/vulkan/vk_platform.h"
#include "backends/vulkan/vk_resources.h"

namespace sb {

class GlfwWindow;

// What GLFW needs enabled on the instance to make a surface (DeviceError when
// GLFW finds no Vulkan loader or no surface extension).
std::vector<const char*> windowInstanceExtensions();
VkSurfaceKHR createWindowSurface(VkInstance instance, GlfwWindow& window);

// The window's swapchain: made at the window's size, remade when the window
// changes size or the surface says it is out of date; nothing is shown while
// the window is minimized. Present mode: immediate where offered (no vsync,
// nothing waits), else mailbox (no tearing, no wait), else fifo (the one mode
// every device has: vsync); `mode()` says which and why.
class VulkanSwapchain {
 public:
  VulkanSwapchain(const VulkanPlatform& platform, VulkanResources& resources);
  ~VulkanSwapchain();
  VulkanSwapchain(const VulkanSwapchain&) = delete;
  VulkanSwapchain& operator=(const VulkanSwapchain&) = delete;

  const std::string& mode() const { return mode_; }
  // Copies layer 0 of `texture` into the next image (scaled, flipped upright),
  // optionally reads that image back, presents it and waits for the copy.
  bool present(TextureRes& texture, PresentedImage* capture);

 private:
  void create();
  void destroySwapchain(VkSwapchainKHR chain);
  bool ensureCurrent();  // false while the window has no area

  const VulkanPlatform& platform_;
  VulkanResources& resources_;
  VkDevice device_ = VK_NULL_HANDLE;
  VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
  std::string mode_;
  VkSurfaceFormatKHR format_{};
  bool canReadBack_ = false;  // the images allow TRANSFER_SRC (capture)
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkExtent2D extent_{0, 0};
  std::vector<VkImage> images_;
  std::vector<VkSemaphore> copied_;  // per image: the copy is done, present may read it
  VkSemaphore acquired_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  VkCommandBuffer cmd_ = VK_NULL_HANDLE;
  bool outdated_ = false;
};

}  // namespace sb
