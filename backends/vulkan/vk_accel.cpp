// Acceleration structures for ray queries (Device::createAccelerationStructure):
// a bottom level of boxes (procedural geometry) under a top level of one
// identity instance, built on the device by one immediate submission.
#include <algorithm>
#include <cstring>
#include <string>

#include "backends/vulkan/vk_resources.h"

namespace sb {

namespace {
constexpr VkDeviceSize kBoxBytes = sizeof(VkAabbPositionsKHR);  // 6 floats
static_assert(kBoxBytes == 24, "the device's box layout (Device::createAccelerationStructure)");
constexpr VkDeviceSize kInstanceBytes = sizeof(VkAccelerationStructureInstanceKHR);

template <class F>
void load(VkDevice device, F& fn, const char* name) {
  fn = reinterpret_cast<F>(vkGetDeviceProcAddr(device, name));
  if (fn == nullptr) throw DeviceError(std::string("vulkan: ") + name + " is missing");
}

// The geometry of one level: the boxes (bottom) or the instance (top), at
// `data` (0 while only sizes are asked).
VkAccelerationStructureGeometryKHR geometry(bool bottom, VkDeviceAddress data) {
  VkAccelerationStructureGeometryKHR g{VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_KHR};
  if (bottom) {
    g.geometryType = VK_GEOMETRY_TYPE_AABBS_KHR;
    g.geometry.aabbs = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_AABBS_DATA_KHR};
    g.geometry.aabbs.data.deviceAddress = data;
    g.geometry.aabbs.stride = kBoxBytes;
    // Not opaque: every candidate reaches the shader, once (the lookup
    // multiplies a transmittance per candidate it accepts).
    g.flags = VK_GEOMETRY_NO_DUPLICATE_ANY_HIT_INVOCATION_BIT_KHR;
  } else {
    g.geometryType = VK_GEOMETRY_TYPE_INSTANCES_KHR;
    g.geometry.instances = {VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_GEOMETRY_INSTANCES_DATA_KHR};
    g.geometry.instances.data.deviceAddress = data;
  }
  return g;
}

VkAccelerationStructureBuildGeometryInfoKHR buildInfo(bool bottom,
                                                      const VkAccelerationStructureGeometryKHR* g) {
  VkAccelerationStructureBuildGeometryInfoKHR b{
      VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_GEOMETRY_INFO_KHR};
  b.type = bottom ? VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR
                  : VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
  b.flags = VK_BUILD_ACCELERATION_STRUCTURE_PREFER_FAST_TRACE_BIT_KHR;
  b.mode = VK_BUILD_ACCELERATION_STRUCTURE_MODE_BUILD_KHR;
  b.geometryCount = 1;
  b.pGeometries = g;
  return b;
}

VkDeviceSize alignUp(VkDeviceSize v, VkDeviceSize a) { return (v + a - 1) / a * a; }
}  // namespace

void VulkanResources::loadAccelerationStructureApi() {
  load(device_, accel_.create, "vkCreateAccelerationStructureKHR");
  load(device_, accel_.destroy, "vkDestroyAccelerationStructureKHR");
  load(device_, accel_.buildSizes, "vkGetAccelerationStructureBuildSizesKHR");
  load(device_, accel_.build, "vkCmdBuildAccelerationStructuresKHR");
  load(device_, accel_.address, "vkGetAccelerationStructureDeviceAddressKHR");
  VkPhysicalDeviceAccelerationStructurePropertiesKHR ap{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_ACCELERATION_STRUCTURE_PROPERTIES_KHR};
  VkPhysicalDeviceProperties2 p2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &ap};
  vkGetPhysicalDeviceProperties2(platform_.physical, &p2);
  accel_.scratchAlignment =
      std::max<VkDeviceSize>(1, ap.minAccelerationStructureScratchOffsetAlignment);
}

VulkanResources::AccelerationSizes VulkanResources::accelerationSizes(uint32_t boxes) const {
  if (accel_.buildSizes == nullptr) throw DeviceError("vulkan: this device has no ray queries");
  AccelerationSizes out;
  VkDeviceSize scratch = 0;
  for (const bool bottom : {true, false}) {
    const VkAccelerationStructureGeometryKHR g = geometry(bottom, 0);
    const VkAccelerationStructureBuildGeometryInfoKHR b = buildInfo(bottom, &g);
    const uint32_t count = bottom ? boxes : 1;
    VkAccelerationStructureBuildSizesInfoKHR sz{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_BUILD_SIZES_INFO_KHR};
    accel_.buildSizes(device_, VK_ACCELERATION_STRUCTURE_BUILD_TYPE_DEVICE_KHR, &b, &count, &sz);
    (bottom ? out.bottom : out.top) = sz.accelerationStructureSize;
    scratch = std::max(scratch, sz.buildScratchSize);
  }
  // One scratch buffer serves both builds (one after the other), with room
  // to align its address.
  out.scratch = scratch + accel_.scratchAlignment;
  return out;
}

std::size_t VulkanResources::accelerationStructureBytes(uint32_t boxes) const {
  const AccelerationSizes s = accelerationSizes(boxes);
  return s.bottom + s.top + s.scratch + boxes * kBoxBytes + kInstanceBytes;
}

AddressedBuffer VulkanResources::createAddressedBuffer(VkDeviceSize bytes, VkBufferUsageFlags usage,
                                                       const std::string& what) {
  AddressedBuffer b;
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = std::max<VkDeviceSize>(bytes, 4);
  ci.usage = usage | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
  ci.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  check(vkCreateBuffer(device_, &ci, nullptr, &b.buffer),
        "vkCreateBuffer (acceleration structure)");
  try {
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device_, b.buffer, &req);
    b.memory = allocate(req, false, what, VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT);
    check(vkBindBufferMemory(device_, b.buffer, b.memory, 0),
          "vkBindBufferMemory (acceleration structure)");
  } catch (...) {
    vkDestroyBuffer(device_, b.buffer, nullptr);
    if (b.memory != VK_NULL_HANDLE) vkFreeMemory(device_, b.memory, nullptr);
    throw;
  }
  VkBufferDeviceAddressInfo ai{VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO};
  ai.buffer = b.buffer;
  b.address = vkGetBufferDeviceAddress(device_, &ai);
  return b;
}

std::unique_ptr<AccelerationStructureRes> VulkanResources::createAccelerationStructure(
    const BufferDesc& desc, const BufferRes& aabbs, uint32_t boxes) {
  const AccelerationSizes sizes = accelerationSizes(boxes);
  auto owned = std::make_unique<AccelerationStructureRes>();
  AccelerationStructureRes& a = *owned;
  a.desc = desc;
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_STORAGE_BIT_KHR;
  const VkBufferUsageFlags input =
      VK_BUFFER_USAGE_ACCELERATION_STRUCTURE_BUILD_INPUT_READ_ONLY_BIT_KHR |
      VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  try {
    const std::string what = "acceleration structure " + desc.name;
    for (auto [bytes, usage] :
         {std::pair{sizes.bottom, storage}, std::pair{sizes.top, storage},
          std::pair{sizes.scratch, VkBufferUsageFlags(VK_BUFFER_USAGE_STORAGE_BUFFER_BIT)},
          std::pair{boxes * kBoxBytes, input}, std::pair{kInstanceBytes, input}})
      a.buffers.push_back(createAddressedBuffer(bytes, usage, what));
    const AddressedBuffer &bottomBuf = a.buffers[0], &topBuf = a.buffers[1],
                          &scratch = a.buffers[2], &boxCopy = a.buffers[3],
                          &instanceBuf = a.buffers[4];
    for (const bool bottom : {true, false}) {
      VkAccelerationStructureCreateInfoKHR ci{
          VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_CREATE_INFO_KHR};
      ci.buffer = (bottom ? bottomBuf : topBuf).buffer;
      ci.size = bottom ? sizes.bottom : sizes.top;
      ci.type = bottom ? VK_ACCELERATION_STRUCTURE_TYPE_BOTTOM_LEVEL_KHR
                       : VK_ACCELERATION_STRUCTURE_TYPE_TOP_LEVEL_KHR;
      check(accel_.create(device_, &ci, nullptr, bottom ? &a.bottom : &a.top),
            "vkCreateAccelerationStructureKHR");
    }
    VkAccelerationStructureDeviceAddressInfoKHR bi{
        VK_STRUCTURE_TYPE_ACCELERATION_STRUCTURE_DEVICE_ADDRESS_INFO_KHR};
    bi.accelerationStructure = a.bottom;
    VkAccelerationStructureInstanceKHR instance{};
    instance.transform.matrix[0][0] = instance.transform.matrix[1][1] =
        instance.transform.matrix[2][2] = 1.0f;
    instance.mask = 0xFF;
    instance.accelerationStructureReference = accel_.address(device_, &bi);
    const VkDeviceAddress scratchAt = alignUp(scratch.address, accel_.scratchAlignment);

    immediate([&](VkCommandBuffer cmd) {
      const VkBufferCopy region{0, 0, boxes * kBoxBytes};
      vkCmdCopyBuffer(cmd, aabbs.buffer, boxCopy.buffer, 1, &region);
      vkCmdUpdateBuffer(cmd, instanceBuf.buffer, 0, kInstanceBytes, &instance);
      for (const bool bottom : {true, false}) {
        fullBarrier(cmd);  // the inputs copied; the bottom level built before the top reads it
        const VkAccelerationStructureGeometryKHR g =
            geometry(bottom, (bottom ? boxCopy : instanceBuf).address);
        VkAccelerationStructureBuildGeometryInfoKHR b = buildInfo(bottom, &g);
        b.dstAccelerationStructure = bottom ? a.bottom : a.top;
        b.scratchData.deviceAddress = scratchAt;
        const VkAccelerationStructureBuildRangeInfoKHR range{bottom ? boxes : 1u, 0, 0, 0};
        const VkAccelerationStructureBuildRangeInfoKHR* ranges = &range;
        accel_.build(cmd, 1, &b, &ranges);
      }
    });
  } catch (...) {
    destroyAccelerationStructure(a);
    throw;
  }
  return owned;
}

void VulkanResources::destroyAccelerationStructure(AccelerationStructureRes& a) {
  for (VkAccelerationStructureKHR* s : {&a.top, &a.bottom}) {
    if (*s != VK_NULL_HANDLE) accel_.destroy(device_, *s, nullptr);
    *s = VK_NULL_HANDLE;
  }
  for (AddressedBuffer& b : a.buffers) {
    vkDestroyBuffer(device_, b.buffer, nullptr);
    vkFreeMemory(device_, b.memory, nullptr);
  }
  a.buffers.clear();
}

}  // namespace sb
