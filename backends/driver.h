// The narrow per-API layer under the Device front end (backends/device.cpp).
// The front end has already checked every call against the device contract
// (handles, frame and pass state, sizes, formats, colour target counts,
// bindings), so a driver only translates: it creates native objects, records
// passes and reads back. It never sees a handle id; it gets back the objects
// it made.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "backends/device.h"

namespace sb {

// What a driver keeps for one buffer, texture or pipeline. The front end owns
// it and hands it back to the driver that made it (which casts it to its type).
struct DriverObject {
  virtual ~DriverObject() = default;
};

struct DriverTexture {
  DriverObject* object = nullptr;
  const TextureDesc* desc = nullptr;
};

struct DriverColorTarget {
  DriverTexture texture;
  LoadOp load = LoadOp::Clear;
  std::array<float, 4> clear{0, 0, 0, 0};
  std::array<uint32_t, 4> clearUint{0, 0, 0, 0};
  uint32_t layer = 0;  // the one layer rendered into (< desc->layers)
  // object null: none. Else a single-sampled texture of the attachment's
  // (float or unorm) format and size, averaged into at the end of the pass.
  DriverTexture resolve;
};

// A pass as checked by the front end: attachments share one size (width x
// height, also for a pass without attachments), no attachment is sampled, no
// layer is attached twice (several layers of one array may be), the depth
// attachment has one layer, and there are at most info().maxColorAttachments
// colour targets (likewise in a pipeline's colorFormats).
struct DriverPass {
  std::string name;
  std::vector<DriverColorTarget> color;
  DriverTexture depth;  // object null: no depth attachment
  LoadOp depthLoad = LoadOp::Clear;
  float depthClear = 1.0f;
  std::vector<DriverTexture> sampled;
  uint32_t width = 0, height = 0;
  uint32_t samples = 1;  // of every attachment (checked equal); 1 without attachments
};

// One binding of a draw or dispatch, in the order the pipeline declares them:
// every declared slot is present once, with an object of its kind.
struct DriverBinding {
  uint32_t binding = 0;
  BindingKind kind = BindingKind::UniformBuffer;
  DriverObject* object = nullptr;
  const BufferDesc* buffer = nullptr;    // buffer kinds
  const TextureDesc* texture = nullptr;  // SampledTexture (one layer), SampledTextureArray
};

// An API's value for one of the device's enums, from a table written in the
// enum's order (each driver keeps one table per enum instead of a switch).
template <class T, std::size_t N, class E>
constexpr T byEnum(const T (&table)[N], E e) {
  return table[static_cast<std::size_t>(e)];
}

// The API's counts of a pass, in this order (PassWork's): input assembly
// vertices and primitives, vertex shader invocations, clipping invocations and
// primitives, fragment and compute shader invocations, samples passed.
using ApiCounts = std::array<uint64_t, 8>;
inline void setApiCounts(PassWork& w, const ApiCounts& v) {
  w.statistics = true;
  w.vertices = v[0];
  w.primitives = v[1];
  w.vertexInvocations = v[2];
  w.clipInvocations = v[3];
  w.clipPrimitives = v[4];
  w.fragmentInvocations = v[5];
  w.computeInvocations = v[6];
  w.samplesPassed = v[7];
}

class Driver {
 public:
  virtual ~Driver() = default;
  // Includes the API's colour attachment limit (maxColorAttachments), which
  // the front end enforces.
  virtual DeviceInfo info() const = 0;

  // Device::memoryBudget(): what the API reports, or the host's for a CPU device.
  virtual MemoryBudget memoryBudget() const = 0;

  // desc.bytes > 0; contents zero unless data is given.
  virtual std::unique_ptr<DriverObject> createBuffer(const BufferDesc& desc, const void* data) = 0;
  // desc.width, desc.height > 0, desc.layers in 1..kMaxTextureLayers (1 for
  // depth); contents zero (colour) or 1 (depth).
  virtual std::unique_ptr<DriverObject> createTexture(const TextureDesc& desc) = 0;
  // Ray queries (info().rayQuery, else never called): the bytes an
  // acceleration structure of `boxes` boxes holds, everything it allocates
  // included, and the structure itself, built on the device from the first
  // `boxes` boxes (24 bytes each) of `aabbs` before this returns.
  virtual std::size_t accelerationStructureBytes(uint32_t boxes) const {
    (void)boxes;
    return 0;
  }
  virtual std::unique_ptr<DriverObject> createAccelerationStructure(const BufferDesc& desc,
                                                                    DriverObject& aabbs,
                                                                    uint32_t boxes) {
    (void)aabbs, (void)boxes;
    throw DeviceError("createAccelerationStructure('" + desc.name + "'): no ray queries on " +
                      info().device);
  }
  // Either vertex+fragment or compute; bindings unique; formats checked.
  virtual std::unique_ptr<DriverObject> createPipeline(const PipelineDesc& desc) = 0;
  // Frees the object now, or once the recorded work of the frame is done.
  virtual void release(std::unique_ptr<DriverObject> object) = 0;
  // After releases outside a frame: whatever the driver below defers freeing
  // is freed before this returns (Device::destroyGroup then trims the heap).
  virtual void finishReleases() {}

  // Outside passes; inside a frame they are ordered with the recorded work.
  virtual void updateBuffer(DriverObject& buffer, const BufferDesc& desc, const void* data,
                            std::size_t bytes, std::size_t offset) = 0;
  virtual void fillBuffer(DriverObject& buffer, const BufferDesc& desc, uint32_t value) = 0;

  virtual void beginFrame() = 0;
  virtual void beginPass(const DriverPass& pass) = 0;
  // The pipeline's colour formats, depth and samples match the open pass.
  virtual void draw(DriverObject& pipeline, const PipelineDesc& desc,
                    const std::vector<DriverBinding>& bindings, uint32_t vertexCount,
                    uint32_t instanceCount) = 0;
  virtual void endPass() = 0;
  virtual void dispatch(const std::string& passName, DriverObject& pipeline,
                        const PipelineDesc& desc, const std::vector<DriverBinding>& bindings,
                        uint32_t x, uint32_t y, uint32_t z) = 0;
  // Submits and waits. The frame is over even when this throws.
  virtual void endFrame() = 0;
  virtual std::vector<PassTiming> lastFrameTimings() const = 0;

  // Outside frames.
  virtual std::vector<uint8_t> readTexture(DriverObject& texture, const TextureDesc& desc) = 0;
  virtual std::vector<uint8_t> readBuffer(DriverObject& buffer, const BufferDesc& desc) = 0;
  // bytes: every layer, tightly packed, as readTexture returns them (size checked).
  virtual void writeTexture(DriverObject& texture, const TextureDesc& desc,
                            const std::vector<uint8_t>& bytes) = 0;

  // Window platforms (Device::present). The front end has checked that the
  // texture is a one-layer colour texture of a float or unorm format and that
  // no frame is open.
  virtual Window* window() { return nullptr; }
  virtual bool present(DriverObject& texture, const TextureDesc& desc, PresentedImage* capture) {
    (void)texture, (void)desc, (void)capture;
    throw DeviceError("present: the " + info().platform +
                      " platform has no window (use --platform window)");
  }
};

}  // namespace sb
