// The Vulkan driver's objects (vk_resources.h): creating and destroying
// buffers, textures and their views, memory and staging buffers, the
// immediate submission and the barriers. Kept apart from vk_driver.cpp so that
// the driver there reads as frames, passes and timing.
#include "backends/vulkan/vk_resources.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace sb {

void fullBarrier(VkCommandBuffer cmd, const std::vector<VkImageMemoryBarrier>& images) {
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  mb.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  mb.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       0, 1, &mb, 0, nullptr, static_cast<uint32_t>(images.size()), images.data());
}

void hostReadBarrier(VkCommandBuffer cmd) {
  VkMemoryBarrier mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  mb.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  mb.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &mb,
                       0, nullptr, 0, nullptr);
}

void transition(std::vector<VkImageMemoryBarrier>& out, TextureRes& t, VkImageLayout layout) {
  if (t.layout == layout) return;
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  b.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  b.oldLayout = t.layout;
  b.newLayout = layout;
  b.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = t.image;
  b.subresourceRange = {t.aspect, 0, 1, 0, VK_REMAINING_ARRAY_LAYERS};
  out.push_back(b);
  t.layout = layout;
}

void resetAndBegin(VkCommandBuffer cmd) {
  check(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer");
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check(vkBeginCommandBuffer(cmd, &bi), "vkBeginCommandBuffer");
}

VulkanResources::VulkanResources(const VulkanPlatform& platform)
    : platform_(platform), device_(platform.device) {
  try {
    VkCommandPoolCreateInfo cp{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    cp.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    cp.queueFamilyIndex = platform.queueFamily;
    check(vkCreateCommandPool(device_, &cp, nullptr, &cmdPool_), "vkCreateCommandPool");
    immCmd_ = allocateCommandBuffer();
    if (platform.info.rayQuery) loadAccelerationStructureApi();
    VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    check(vkCreateFence(device_, &fi, nullptr, &fence_), "vkCreateFence");
  } catch (...) {
    destroy();
    throw;
  }
}

VulkanResources::~VulkanResources() { destroy(); }

void VulkanResources::destroy() {
  if (fence_ != VK_NULL_HANDLE) vkDestroyFence(device_, fence_, nullptr);
  if (cmdPool_ != VK_NULL_HANDLE) vkDestroyCommandPool(device_, cmdPool_, nullptr);
  fence_ = VK_NULL_HANDLE;
  cmdPool_ = VK_NULL_HANDLE;
}

VkCommandBuffer VulkanResources::allocateCommandBuffer() {
  VkCommandBufferAllocateInfo ca{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ca.commandPool = cmdPool_;
  ca.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ca.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  check(vkAllocateCommandBuffers(device_, &ca, &cmd), "vkAllocateCommandBuffers");
  return cmd;
}

void VulkanResources::submitAndWait(VkCommandBuffer cmd) {
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  check(vkQueueSubmit(platform_.queue, 1, &si, fence_), "vkQueueSubmit");
  check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  check(vkResetFences(device_, 1, &fence_), "vkResetFences");
}

VkDeviceMemory VulkanResources::allocate(const VkMemoryRequirements& req, bool host,
                                         const std::string& what, VkMemoryAllocateFlags flags) {
  const VkPhysicalDeviceMemoryProperties& memProps = platform_.memProps;
  const VkMemoryPropertyFlags want =
      host ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
           : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  uint32_t type = UINT32_MAX;
  for (uint32_t i = 0; i < memProps.memoryTypeCount && type == UINT32_MAX; ++i) {
    if ((req.memoryTypeBits & (1u << i)) != 0 &&
        (memProps.memoryTypes[i].propertyFlags & want) == want) {
      type = i;
    }
  }
  if (type == UINT32_MAX && !host) {  // no device-local type fits: take any
    for (uint32_t i = 0; i < memProps.memoryTypeCount && type == UINT32_MAX; ++i) {
      if ((req.memoryTypeBits & (1u << i)) != 0) type = i;
    }
  }
  if (type == UINT32_MAX) throw DeviceError("vulkan: no memory type for " + what);
  VkMemoryAllocateFlagsInfo fi{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO};
  fi.flags = flags;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, flags != 0 ? &fi : nullptr};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = type;
  VkDeviceMemory mem = VK_NULL_HANDLE;
  VkResult r = vkAllocateMemory(device_, &ai, nullptr, &mem);
  if (r != VK_SUCCESS) {
    const std::string m = "vulkan: allocating " + std::to_string(req.size) + " bytes for " + what +
                          " failed: " + resultName(r);
    if (r == VK_ERROR_OUT_OF_HOST_MEMORY || r == VK_ERROR_OUT_OF_DEVICE_MEMORY)
      throw OutOfMemoryError(m);
    throw DeviceError(m);
  }
  return mem;
}

HostBuffer VulkanResources::createHostBuffer(VkDeviceSize bytes) {
  HostBuffer h;
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = std::max<VkDeviceSize>(bytes, 4);
  ci.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(device_, &ci, nullptr, &h.buffer), "vkCreateBuffer (staging)");
  try {
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, h.buffer, &req);
    h.memory = allocate(req, true, "staging buffer");
    check(vkBindBufferMemory(device_, h.buffer, h.memory, 0), "vkBindBufferMemory (staging)");
    check(vkMapMemory(device_, h.memory, 0, VK_WHOLE_SIZE, 0, &h.mapped), "vkMapMemory");
  } catch (...) {
    destroyHostBuffer(h);
    throw;
  }
  return h;
}

void VulkanResources::destroyHostBuffer(HostBuffer& h) {
  if (h.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device_, h.buffer, nullptr);
  if (h.memory != VK_NULL_HANDLE) vkFreeMemory(device_, h.memory, nullptr);  // unmaps
  h = HostBuffer{};
}

std::unique_ptr<BufferRes> VulkanResources::createBuffer(const BufferDesc& desc, const void* data) {
  auto r = std::make_unique<BufferRes>();
  r->desc = desc;
  r->size = std::max<VkDeviceSize>(4, (desc.bytes + 3) / 4 * 4);
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = r->size;
  // Both uniform and storage usage: GL buffers are untyped, so are these.
  ci.usage = VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
             VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(device_, &ci, nullptr, &r->buffer), "vkCreateBuffer");
  try {
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, r->buffer, &req);
    r->memory = allocate(req, false, "buffer " + desc.name);
    check(vkBindBufferMemory(device_, r->buffer, r->memory, 0), "vkBindBufferMemory");
    // Defined contents (zero) unless data is given, as on GL.
    const auto zero = [&](VkCommandBuffer cmd) {
      vkCmdFillBuffer(cmd, r->buffer, 0, VK_WHOLE_SIZE, 0);
    };
    if (data == nullptr) {
      immediate(zero);
    } else {
      upload(data, desc.bytes, [&](VkCommandBuffer cmd, VkBuffer staging) {
        zero(cmd);
        fullBarrier(cmd);
        VkBufferCopy region{0, 0, desc.bytes};
        vkCmdCopyBuffer(cmd, staging, r->buffer, 1, &region);
      });
    }
  } catch (...) {
    destroyBuffer(*r);
    throw;
  }
  return r;
}

std::unique_ptr<TextureRes> VulkanResources::createTexture(const TextureDesc& desc) {
  auto owned = std::make_unique<TextureRes>();
  TextureRes& t = *owned;
  t.desc = desc;
  t.format = toVkFormat(desc.format);
  const bool depth = isDepthFormat(desc.format);
  t.aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;

  VkFormatProperties fp;
  vkGetPhysicalDeviceFormatProperties(platform_.physical, t.format, &fp);
  const VkFormatFeatureFlags have = fp.optimalTilingFeatures;
  const VkFormatFeatureFlags need = (depth ? VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT
                                           : VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) |
                                    VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                    VK_FORMAT_FEATURE_TRANSFER_SRC_BIT |
                                    VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
  if ((have & need) != need) {
    throw DeviceError(std::string("createTexture('") + desc.name + "'): format " +
                      formatName(desc.format) +
                      " cannot be a render target, sampled and copied on " + platform_.info.device);
  }
  t.linear = desc.linearFilter;
  if (t.linear && (isIntegerFormat(desc.format) ||
                   (have & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) == 0)) {
    std::fprintf(stderr,
                 "strandbench: vulkan: texture '%s' (%s) cannot be filtered linearly on this "
                 "device; sampling it nearest\n",
                 desc.name.c_str(), formatName(desc.format));
    t.linear = false;
  }

  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = t.format;
  ci.extent = {desc.width, desc.height, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = desc.layers;
  ci.samples = static_cast<VkSampleCountFlagBits>(desc.samples);
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  const bool multisampled = desc.samples > 1;
  // A multisampled texture is only a render target (cleared once by transfer).
  ci.usage =
      (depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) |
      VK_IMAGE_USAGE_TRANSFER_DST_BIT |
      (multisampled ? 0u : VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  if (!depth && !multisampled && (have & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) != 0) {
    ci.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
  }
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  check(vkCreateImage(device_, &ci, nullptr, &t.image), "vkCreateImage");
  try {
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device_, t.image, &req);
    t.memory = allocate(req, false, "texture " + desc.name);
    check(vkBindImageMemory(device_, t.image, t.memory, 0), "vkBindImageMemory");
    if (desc.layers == 1) t.view = makeView(t, VK_IMAGE_VIEW_TYPE_2D, 0, 1);
    if (!multisampled) t.arrayView = makeView(t, VK_IMAGE_VIEW_TYPE_2D_ARRAY, 0, desc.layers);
    t.layerViews.assign(desc.layers > 1 ? desc.layers : 0, VK_NULL_HANDLE);
    // Defined initial contents: colour 0, depth 1 (far). A fresh resource, so an
    // immediate submission is ordered correctly even inside a frame.
    immediate([&](VkCommandBuffer cmd) {
      std::vector<VkImageMemoryBarrier> barriers;
      transition(barriers, t, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
      fullBarrier(cmd, barriers);
      VkImageSubresourceRange range{t.aspect, 0, 1, 0, desc.layers};
      if (depth) {
        VkClearDepthStencilValue v{1.0f, 0};
        vkCmdClearDepthStencilImage(cmd, t.image, t.layout, &v, 1, &range);
      } else {
        VkClearColorValue v{};
        vkCmdClearColorImage(cmd, t.image, t.layout, &v, 1, &range);
      }
    });
  } catch (...) {
    destroyTexture(t);
    throw;
  }
  return owned;
}

VkImageView VulkanResources::makeView(const TextureRes& t, VkImageViewType type, uint32_t first,
                                      uint32_t count) {
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = t.image;
  vi.viewType = type;
  vi.format = t.format;
  vi.subresourceRange = {t.aspect, 0, 1, first, count};
  VkImageView v = VK_NULL_HANDLE;
  check(vkCreateImageView(device_, &vi, nullptr, &v), "vkCreateImageView");
  return v;
}

VkImageView VulkanResources::attachmentView(TextureRes& t, uint32_t layer) {
  if (t.layerViews.empty()) return t.view;
  VkImageView& v = t.layerViews[layer];
  if (v == VK_NULL_HANDLE) v = makeView(t, VK_IMAGE_VIEW_TYPE_2D, layer, 1);
  return v;
}

void VulkanResources::destroyBuffer(BufferRes& b) {
  if (b.buffer != VK_NULL_HANDLE) vkDestroyBuffer(device_, b.buffer, nullptr);
  if (b.memory != VK_NULL_HANDLE) vkFreeMemory(device_, b.memory, nullptr);
  b.buffer = VK_NULL_HANDLE;
  b.memory = VK_NULL_HANDLE;
}

void VulkanResources::destroyTexture(TextureRes& t) {
  for (VkImageView v : t.layerViews)
    if (v != VK_NULL_HANDLE) vkDestroyImageView(device_, v, nullptr);
  t.layerViews.clear();
  if (t.arrayView != VK_NULL_HANDLE) vkDestroyImageView(device_, t.arrayView, nullptr);
  t.arrayView = VK_NULL_HANDLE;
  if (t.view != VK_NULL_HANDLE) vkDestroyImageView(device_, t.view, nullptr);
  if (t.image != VK_NULL_HANDLE) vkDestroyImage(device_, t.image, nullptr);
  if (t.memory != VK_NULL_HANDLE) vkFreeMemory(device_, t.memory, nullptr);
  t.view = VK_NULL_HANDLE;
  t.image = VK_NULL_HANDLE;
  t.memory = VK_NULL_HANDLE;
}

void VulkanResources::destroyPipeline(PipelineRes& p) {
  if (p.pipeline != VK_NULL_HANDLE) vkDestroyPipeline(device_, p.pipeline, nullptr);
  if (p.layout != VK_NULL_HANDLE) vkDestroyPipelineLayout(device_, p.layout, nullptr);
  if (p.setLayout != VK_NULL_HANDLE) {
    vkDestroyDescriptorSetLayout(device_, p.setLayout, nullptr);
  }
  p.pipeline = VK_NULL_HANDLE;
  p.layout = VK_NULL_HANDLE;
  p.setLayout = VK_NULL_HANDLE;
}

void VulkanResources::destroyObject(DriverObject& object) {
  if (auto* b = dynamic_cast<BufferRes*>(&object)) destroyBuffer(*b);
  if (auto* t = dynamic_cast<TextureRes*>(&object)) destroyTexture(*t);
  if (auto* p = dynamic_cast<PipelineRes*>(&object)) destroyPipeline(*p);
  if (auto* a = dynamic_cast<AccelerationStructureRes*>(&object)) destroyAccelerationStructure(*a);
}

}  // namespace sb
