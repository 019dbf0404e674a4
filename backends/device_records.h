// The Device's records behind its handles and the helpers its two source files
// share (device.cpp: the tables, frame and pass state, contract checks;
// device_memory.cpp: making resources on first use, accounting, the memory plan's
// guard). Included by those two files only.
#pragma once

#include <cstdio>
#include <memory>
#include <new>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "backends/device.h"
#include "backends/driver.h"

namespace sb {

struct Device::BufferRec {
  BufferDesc desc;
  std::unique_ptr<DriverObject> object;
  uint32_t group = 0;  // the ResourceGroup current at creation (0: none)
  // An acceleration structure's boxes (usage AccelerationStructure).
  Buffer aabbs;
  uint32_t boxes = 0;
  // The contents it was created with, kept until it is made (setDeferMaking).
  std::vector<uint8_t> pending;
};
struct Device::TextureRec {
  TextureDesc desc;
  std::unique_ptr<DriverObject> object;
  uint32_t group = 0;
};
struct Device::PipelineRec {
  PipelineDesc desc;  // fixed state only: the shader pointers are not kept
  std::unique_ptr<DriverObject> object;
  bool compute = false;
  uint32_t group = 0;
  // A deferred pipeline's shaders (vertex, fragment or compute alone) until it is compiled.
  std::vector<ShaderCode> shaders;
  bool mesh = false;  // its vertex shader is a mesh shader (ShaderCode::meshGroupVertices)
};
struct Device::OpenPass {
  std::string name;
  std::vector<uint32_t> attachments, sampled;
  std::vector<uint32_t> attachmentLayers;  // the layer of each attachment
  std::vector<Format> colorFormats;
  bool hasDepth = false;
  uint32_t samples = 0;  // of its attachments (0 until the first)
  PassWork work;         // the front end's counts (PassWork)
  std::set<std::tuple<char, uint32_t, uint32_t>> touched;
};

namespace device_detail {

inline std::string quoted(const std::string& op, const std::string& name) {
  return op + "('" + name + "')";
}

// Every sample of a multisampled texture counts.
inline std::size_t textureBytes(const TextureDesc& d) {
  return std::size_t{d.width} * d.height * d.layers * d.samples * bytesPerPixel(d.format);
}

inline std::string mib(std::size_t bytes) {
  char text[48];
  std::snprintf(text, sizeof text, "%zu bytes (%.2f MiB)", bytes, double(bytes) / (1 << 20));
  return text;
}

// Runs an allocation; a failed one (the host's std::bad_alloc, or the API's
// out-of-memory error that the driver threw as OutOfMemoryError) becomes one
// OutOfMemoryError that names what was being allocated and its size.
template <class F>
auto namingAllocation(const std::string& what, std::size_t bytes, F&& allocate) {
  const std::string size = bytes ? ", " + mib(bytes) : "";
  try {
    return allocate();
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError("out of memory " + what + size + ": a host allocation failed");
  } catch (const OutOfMemoryError& e) {
    throw OutOfMemoryError("out of memory " + what + size + ": " + e.what());
  }
}

// The record behind a handle, or a DeviceError naming the call and the handle.
template <class Table>
auto& record(Table& table, uint32_t id, const char* kind, const std::string& where) {
  auto it = table.find(id);
  if (it == table.end())
    throw DeviceError(where + ": unknown " + kind + " handle " + std::to_string(id));
  return *it->second;
}

}  // namespace device_detail
}  // namespace sb
