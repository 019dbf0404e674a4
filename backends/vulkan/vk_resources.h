// The Vulkan driver's objects and how they are made, apart from the recording
// of frames (vk_driver.cpp), which only uses them: buffers, textures (with
// their per-layer views) and pipelines as the front end holds them, memory
// allocation, host-visible staging buffers, the one-shot "immediate"
// submission used outside frames, and the barriers and layout transitions
// shared by both.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "backends/driver.h"
#include "backends/vulkan/vk_platform.h"
#include "backends/vulkan/vk_util.h"

namespace sb {

struct BufferRes : DriverObject {
  BufferDesc desc;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;  // allocated size (>= desc.bytes, multiple of 4, at least 4)
};

struct TextureRes : DriverObject {
  TextureDesc desc;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = VK_IMAGE_ASPECT_COLOR_BIT;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;       // 2D (one layer): attachment and sampler2D
  VkImageView arrayView = VK_NULL_HANDLE;  // 2D_ARRAY of every layer: sampler2DArray
  std::vector<VkImageView> layerViews;     // layers > 1: 2D of one layer, made when attached
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // of every layer (they move together)
  bool linear = false;  // sampler actually used (linear may fall back to nearest)
};

struct PipelineRes : DriverObject {
  // Uniform buffer bindings the shaders read as storage buffers
  // (VulkanPlatform::uniformsAsStorage): bound with storage buffer descriptors.
  std::set<uint32_t> uniformsAsStorage;
  VkPipeline pipeline = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  uint32_t meshGroupVertices = 0;  // a mesh pipeline (ShaderCode::meshGroupVertices)
};

// A device buffer with its own memory and device address (the parts of an
// acceleration structure).
struct AddressedBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceAddress address = 0;
};

// Device::createAccelerationStructure: the top level (bound to shaders) over
// the bottom level of boxes, and every buffer they were built from, kept for
// the structure's life (so what it holds is what the front end counted).
struct AccelerationStructureRes : DriverObject {
  BufferDesc desc;
  VkAccelerationStructureKHR bottom = VK_NULL_HANDLE, top = VK_NULL_HANDLE;
  std::vector<AddressedBuffer> buffers;  // bottom, top, scratch, boxes, instance
};

// The VK_KHR_acceleration_structure entry points (device functions).
struct AccelerationStructureApi {
  PFN_vkCreateAccelerationStructureKHR create = nullptr;
  PFN_vkDestroyAccelerationStructureKHR destroy = nullptr;
  PFN_vkGetAccelerationStructureBuildSizesKHR buildSizes = nullptr;
  PFN_vkCmdBuildAccelerationStructuresKHR build = nullptr;
  PFN_vkGetAccelerationStructureDeviceAddressKHR address = nullptr;
  VkDeviceSize scratchAlignment = 1;  // minAccelerationStructureScratchOffsetAlignment
};

struct HostBuffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
};

// A full memory barrier (all commands -> all commands, memory write -> memory
// read|write) carrying the given image barriers.
void fullBarrier(VkCommandBuffer cmd, const std::vector<VkImageMemoryBarrier>& images = {});
// Transfer writes -> host reads, before mapping a readback buffer.
void hostReadBarrier(VkCommandBuffer cmd);
// Appends a layout transition (if needed) and updates the tracked layout.
void transition(std::vector<VkImageMemoryBarrier>& out, TextureRes& t, VkImageLayout layout);
// Resets cmd and begins recording it for one submission.
void resetAndBegin(VkCommandBuffer cmd);

// Makes and destroys the driver's objects on the platform's device, and owns
// the command pool (the frame's command buffer comes from it too), the
// immediate command buffer and the fence every submission waits on.
class VulkanResources {
 public:
  explicit VulkanResources(const VulkanPlatform& platform);  // the platform outlives it
  ~VulkanResources();
  VulkanResources(const VulkanResources&) = delete;
  VulkanResources& operator=(const VulkanResources&) = delete;

  // A primary command buffer, resettable, freed with the pool.
  VkCommandBuffer allocateCommandBuffer();
  // Submits cmd alone to the queue and waits for it.
  void submitAndWait(VkCommandBuffer cmd);
  // Records with record(cmd) into the immediate command buffer, submits and waits.
  template <class F>
  void immediate(F&& record) {
    resetAndBegin(immCmd_);
    record(immCmd_);
    check(vkEndCommandBuffer(immCmd_), "vkEndCommandBuffer");
    submitAndWait(immCmd_);
  }

  // Device-local memory (any type where none fits), or host-visible coherent;
  // flags: VkMemoryAllocateFlags (device addresses).
  VkDeviceMemory allocate(const VkMemoryRequirements& req, bool host, const std::string& what,
                          VkMemoryAllocateFlags flags = 0);
  // A mapped host buffer of at least `bytes` (at least 4), for transfers both ways.
  HostBuffer createHostBuffer(VkDeviceSize bytes);
  void destroyHostBuffer(HostBuffer& h);
  // Calls use(staging) with a fresh host buffer of `bytes`, destroyed after it
  // (also when use throws).
  template <class F>
  void withHostBuffer(VkDeviceSize bytes, F&& use) {
    HostBuffer staging = createHostBuffer(bytes);
    try {
      use(staging);
    } catch (...) {
      destroyHostBuffer(staging);
      throw;
    }
    destroyHostBuffer(staging);
  }
  // The two ways of staging: upload copies `bytes` of data into a host buffer,
  // then record(cmd, staging) copies it onward; download has record(cmd, staging)
  // copy into a host buffer, made visible to the host, and returns its `bytes`.
  // Each submits and waits.
  template <class F>
  void upload(const void* data, VkDeviceSize bytes, F&& record) {
    withHostBuffer(bytes, [&](HostBuffer& staging) {
      std::memcpy(staging.mapped, data, bytes);
      immediate([&](VkCommandBuffer cmd) { record(cmd, staging.buffer); });
    });
  }
  template <class F>
  std::vector<uint8_t> download(VkDeviceSize bytes, F&& record) {
    std::vector<uint8_t> out(bytes);
    withHostBuffer(bytes, [&](HostBuffer& staging) {
      immediate([&](VkCommandBuffer cmd) {
        record(cmd, staging.buffer);
        hostReadBarrier(cmd);
      });
      std::memcpy(out.data(), staging.mapped, out.size());
    });
    return out;
  }

  // Contents zero unless data is given (desc.bytes of it). Waits for the upload.
  std::unique_ptr<BufferRes> createBuffer(const BufferDesc& desc, const void* data);
  // Contents zero (colour) or 1 (depth). Throws DeviceError when the format
  // cannot be a render target, sampled and copied; falls back to nearest
  // filtering (with a warning) where linear is asked for but not possible.
  std::unique_ptr<TextureRes> createTexture(const TextureDesc& desc);
  // The view a pass renders into: the texture's own, or its layer's (made once).
  VkImageView attachmentView(TextureRes& t, uint32_t layer);

  // Ray queries (vk_accel.cpp; the platform's info.rayQuery): the bytes
  // createAccelerationStructure will hold for `boxes` boxes, and the structure,
  // built from the first `boxes` boxes of `aabbs` (copied) before it returns.
  std::size_t accelerationStructureBytes(uint32_t boxes) const;
  std::unique_ptr<AccelerationStructureRes> createAccelerationStructure(const BufferDesc& desc,
                                                                        const BufferRes& aabbs,
                                                                        uint32_t boxes);
  void destroyAccelerationStructure(AccelerationStructureRes& a);

  void destroyBuffer(BufferRes& b);
  void destroyTexture(TextureRes& t);
  void destroyPipeline(PipelineRes& p);
  void destroyObject(DriverObject& object);  // whichever of the four it is

 private:
  VkImageView makeView(const TextureRes& t, VkImageViewType type, uint32_t first, uint32_t count);
  void destroy();
  struct AccelerationSizes {
    VkDeviceSize bottom = 0, top = 0, scratch = 0;
  };
  AccelerationSizes accelerationSizes(uint32_t boxes) const;
  AddressedBuffer createAddressedBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage,
                                        const std::string& what);

  void loadAccelerationStructureApi();
  AccelerationStructureApi accel_;  // loaded where the device has ray queries

  const VulkanPlatform& platform_;
  VkDevice device_ = VK_NULL_HANDLE;
  VkCommandPool cmdPool_ = VK_NULL_HANDLE;
  VkCommandBuffer immCmd_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace sb
