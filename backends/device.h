// The one small interface techniques call: the Device front end below, over a
// driver that GL and Vulkan each implement once (backends/gl, backends/vulkan);
// nothing above backends/ names either API.
//
// Conventions shared by both backends (so images match pixel for pixel):
//  - NDC y=-1 is memory row 0, texture v=0 is row 0, depth range is [0,1]
//    (GL uses glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), Vulkan no y-flip).
//  - No vertex input: shaders pull vertices from storage buffers by
//    gl_VertexIndex, so pipelines carry no vertex layout.
//  - Binding numbers are unique across kinds within a shader (set 0 in Vulkan).
//  - Work is recorded between beginFrame() and endFrame(); endFrame() waits for
//    completion and makes per-pass timings available.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "backends/owner.h"
#include "base/errors.h"  // DeviceError

namespace sb {

enum class Format {
  RGBA8,  // unorm
  RGBA16F,
  RGBA32F,
  R32F,
  RG32F,
  R32UI,
  RGBA32UI,
  Depth32F,
};
std::size_t bytesPerPixel(Format f);
bool isDepthFormat(Format f);
bool isIntegerFormat(Format f);
const char* formatName(Format f);

// Handles are plain ids; 0 means "none". The device owns every resource.
struct Buffer {
  uint32_t id = 0;
  explicit operator bool() const { return id != 0; }
};
struct Texture {
  uint32_t id = 0;
  explicit operator bool() const { return id != 0; }
};
struct Pipeline {
  uint32_t id = 0;
  explicit operator bool() const { return id != 0; }
};

// AccelerationStructure: made by Device::createAccelerationStructure only.
enum class BufferUsage { Uniform, Storage, AccelerationStructure };

struct BufferDesc {
  std::string name;  // reported in memory accounting
  Owner owner = Owner::None;
  BufferUsage usage = BufferUsage::Storage;
  std::size_t bytes = 0;
};

struct TextureDesc {
  std::string name;
  Owner owner = Owner::None;
  Format format = Format::RGBA8;
  uint32_t width = 1, height = 1;
  // Every texture can be a render target, sampled and read back. Sampling is
  // nearest or linear, always clamp-to-edge.
  bool linearFilter = false;
  // A 2D array of `layers` images of one format and size (1..kMaxTextureLayers;
  // depth textures have one). A pass renders into one layer per attachment
  // (ColorAttachment::layer); shaders sample the whole array through a
  // SampledTextureArray slot (sampler2DArray / usampler2DArray, any layer
  // count, one layer included) and a one-layer texture also through a
  // SampledTexture slot (sampler2D). Read-back returns the layers in order.
  uint32_t layers = 1;
  // Samples per pixel (1, or a count in DeviceInfo::sampleCounts). A
  // multisampled texture has one layer and is only a render target: it is
  // never sampled, read back or written; a pass resolves it into a
  // single-sampled texture (ColorAttachment::resolve) that is. Memory counts
  // every sample.
  uint32_t samples = 1;
};
// The most layers a texture may have: the least both APIs guarantee (Vulkan's
// maxImageArrayLayers; GL 4.5 guarantees 2048).
constexpr uint32_t kMaxTextureLayers = 256;

enum class Topology { Lines, Triangles };
enum class CompareOp { Never, Less, LessEqual, Equal, Greater, GreaterEqual, NotEqual, Always };
enum class BlendFactor {
  Zero,
  One,
  SrcColor,
  OneMinusSrcColor,
  SrcAlpha,
  OneMinusSrcAlpha,
  DstColor,
  OneMinusDstColor,
  DstAlpha,
  OneMinusDstAlpha,
};
enum class BlendOp { Add, Subtract, ReverseSubtract, Min, Max };

struct BlendState {
  bool enable = false;
  BlendFactor srcColor = BlendFactor::One, dstColor = BlendFactor::Zero;
  BlendOp colorOp = BlendOp::Add;
  BlendFactor srcAlpha = BlendFactor::One, dstAlpha = BlendFactor::Zero;
  BlendOp alphaOp = BlendOp::Add;

  static BlendState replace() { return {}; }
  // Non-premultiplied "over": c = a*src + (1-a)*dst, alpha likewise.
  static BlendState over() {
    return {true,         BlendFactor::SrcAlpha, BlendFactor::OneMinusSrcAlpha,
            BlendOp::Add, BlendFactor::One,      BlendFactor::OneMinusSrcAlpha,
            BlendOp::Add};
  }
  static BlendState additive() {
    return {true,         BlendFactor::One, BlendFactor::One,
            BlendOp::Add, BlendFactor::One, BlendFactor::One,
            BlendOp::Add};
  }
  static BlendState min() {
    return {true,         BlendFactor::One, BlendFactor::One,
            BlendOp::Min, BlendFactor::One, BlendFactor::One,
            BlendOp::Min};
  }
  static BlendState max() {
    return {true,         BlendFactor::One, BlendFactor::One,
            BlendOp::Max, BlendFactor::One, BlendFactor::One,
            BlendOp::Max};
  }
};

// SampledTexture: sampler2D of a one-layer texture; SampledTextureArray:
// sampler2DArray of any texture (a one-layer texture is an array of one).
// AccelerationStructure: accelerationStructureEXT (GL_EXT_ray_query), a buffer
// made by Device::createAccelerationStructure.
enum class BindingKind {
  UniformBuffer,
  StorageBuffer,
  SampledTexture,
  SampledTextureArray,
  AccelerationStructure,
};

struct BindingSlot {
  uint32_t binding = 0;
  BindingKind kind = BindingKind::UniformBuffer;
};

// A shader as given to the device: already preprocessed (see shader_source.h),
// with the table that maps its line numbers back to files for error messages.
struct ShaderCode {
  std::string name;                    // e.g. "techniques/shadowmap/depth.frag"
  std::string text;                    // GLSL 4.50 body without #version / preamble
  std::vector<std::string> fileNames;  // index = source-string number used in #line
  // > 0: a mesh shader given as a pipeline's vertex shader (Vulkan with
  // info().meshShaders; Device::meshPipelineRefusal), which keeps the vertex
  // path's draw: a draw of vertexCount vertices (one instance) runs
  // ceil(vertexCount / meshGroupVertices) workgroups, each emitting the primitives of
  // its vertices. The groups are laid out in rows (gl_NumWorkGroups.x wide): the
  // shader's group is y * gl_NumWorkGroups.x + x, and the last row's extra groups
  // emit nothing.
  uint32_t meshGroupVertices = 0;
};

struct PipelineDesc {
  std::string name;
  std::string technique;  // named in compile errors
  // Either vertex+fragment (graphics) or compute alone. The vertex shader may be a
  // mesh shader standing in for it (ShaderCode::meshGroupVertices): a mesh pipeline.
  const ShaderCode* vertex = nullptr;
  const ShaderCode* fragment = nullptr;
  const ShaderCode* compute = nullptr;
  Topology topology = Topology::Triangles;
  std::vector<Format> colorFormats;  // render-target formats, in attachment order
  Format depthFormat = Format::Depth32F;
  bool hasDepth = false;
  bool depthTest = false;
  bool depthWrite = false;
  CompareOp depthCompare = CompareOp::Less;
  std::vector<BlendState> blend;  // one per colour target (empty: replace)
  bool logicOpOr = false;         // bitwise OR into integer targets (both APIs: all targets)
  std::vector<BindingSlot> bindings;
  // Rasterization samples: the sample count of the passes it draws in (checked
  // at each draw). With more than one, the fragment shader may write
  // gl_SampleMask (ANDed with the geometric coverage), depth is tested per
  // sample, and lines are rasterized as the API's multisampled lines.
  uint32_t samples = 1;
};

enum class LoadOp { Clear, Load };

// Always one layer of its texture: an array texture is attached layer by
// layer (several layers of one array may be attachments of one pass; the whole
// array at once, layered rendering, is not offered).
struct ColorAttachment {
  Texture texture;
  LoadOp load = LoadOp::Clear;
  std::array<float, 4> clear{0, 0, 0, 0};         // float/unorm formats
  std::array<uint32_t, 4> clearUint{0, 0, 0, 0};  // integer formats
  uint32_t layer = 0;                             // < the texture's layers
  // A multisampled attachment may name a single-sampled texture of its format
  // (float or unorm) and size: at the end of the pass its samples are averaged
  // into it (GL: a framebuffer blit; Vulkan: the rendering's resolve
  // attachment). The resolve target is written by the pass.
  Texture resolve;
};

struct DepthAttachment {
  Texture texture;  // none: no depth
  LoadOp load = LoadOp::Clear;
  float clear = 1.0f;
};

// A render pass: what it writes (attachments) and what it reads (textures
// sampled, buffers), declared up front so the backend can order and
// transition resources, and so time and memory are reported per pass.
struct PassDesc {
  std::string name;
  std::vector<ColorAttachment> color;
  DepthAttachment depth;
  std::vector<Texture> sampledTextures;
  // Size of a pass without attachments (fragments write storage buffers only);
  // ignored when the pass has attachments.
  uint32_t width = 0, height = 0;
};

struct Binding {
  uint32_t binding = 0;
  Buffer buffer;  // buffer kinds and AccelerationStructure
  Texture texture;
  static Binding buf(uint32_t b, Buffer x) { return {b, x, {}}; }
  static Binding tex(uint32_t b, Texture t) { return {b, {}, t}; }
};

// A resource a pass touches, as the work counters count it: its whole bound
// extent (an attachment: the one layer attached, all its samples).
struct PassResource {
  std::string name;
  std::string format;                                       // formatName, or "buffer"
  uint32_t width = 0, height = 0, layers = 0, samples = 0;  // 0 for buffers
  uint64_t bytes = 0;
  std::string access;  // "write" (attachment), "read" (sampled, uniform, loaded
                       // attachment: both), "storage" (read and/or written)
  bool operator==(const PassResource&) const = default;
};

// The work a pass did, counted exactly: the same case gives the same counts on
// every run. The first group is what the API's queries report (pipeline
// statistics, and an occlusion query in render passes); `statistics` is false,
// and they are zero, where the device has no such queries. The rest the front
// end counts from what the pass declared and recorded.
struct PassWork {
  bool statistics = false;
  uint64_t vertices = 0;             // input assembly vertices
  uint64_t primitives = 0;           // input assembly primitives
  uint64_t vertexInvocations = 0;    // vertex shader invocations
  uint64_t clipInvocations = 0;      // primitives entering clipping
  uint64_t clipPrimitives = 0;       // primitives leaving clipping
  uint64_t fragmentInvocations = 0;  // fragment shader invocations
  uint64_t computeInvocations = 0;   // compute shader invocations
  uint64_t samplesPassed = 0;        // samples passing the depth test (render passes)
  uint32_t draws = 0, dispatches = 0;
  uint64_t bytesWritten = 0, bytesRead = 0, bytesStorage = 0;  // by PassResource::access
  std::vector<PassResource> resources;                         // each once per pass execution
  // Another execution of the same pass (frames sum a pass's executions).
  PassWork& operator+=(const PassWork& o);
  bool operator==(const PassWork&) const = default;
};

struct PassTiming {
  std::string name;
  double ms = 0;
  double startMs = 0;  // from the frame's start, on the same clock as ms (traces)
  PassWork work;
};

struct ResourceBytes {
  std::string name;
  Owner owner = Owner::None;
  std::size_t bytes = 0;
};

struct DeviceInfo {
  std::string backend;   // "gl" | "vulkan"
  std::string platform;  // "egl" | "osmesa" | "headless"
  std::string device;    // renderer / deviceName
  std::string driver;    // version string / driverInfo
  // Which driver the process runs (backends/driver_env.h): "system", the name of a
  // folder under drivers/ ("mesa-25.0") or its path.
  std::string driverName;
  std::string apiVersion;  // GL: "4.5"; Vulkan: the device's "1.3.230"
  std::string timing;      // how pass times are measured
  std::string counters;    // which API queries fill PassWork ("" : none)
  std::string lines;       // how Lines topology is rasterized
  // Window platforms: how present() shows an image (GL swap interval; Vulkan
  // present mode and why it was chosen). Empty on headless platforms.
  std::string present;
  // The most colour attachments a pass or a pipeline may have (GL: the lesser
  // of GL_MAX_DRAW_BUFFERS and GL_MAX_COLOR_ATTACHMENTS, 8 or more; Vulkan:
  // maxColorAttachments, 4 or more).
  uint32_t maxColorAttachments = 0;
  // Ordered per-pixel read-modify-write in fragment shaders (GL:
  // GL_ARB_fragment_shader_interlock; Vulkan: VK_EXT_fragment_shader_interlock).
  // Absent on Mesa's CPU rasterizers: mlab then emulates the order in a resolve.
  bool fragmentShaderInterlock = false;
  // Capabilities `strandbench --version` lists per driver: ray queries (Vulkan:
  // VK_KHR_ray_query with VK_KHR_acceleration_structure and buffer device
  // addresses, their features enabled; GL has none: createAccelerationStructure
  // and AccelerationStructure slots need it), mesh shaders (VK_EXT_mesh_shader;
  // GL_EXT_mesh_shader / GL_NV_mesh_shader) and timestamp queries (Vulkan: the
  // queue's timestampValidBits; GL: core since 3.3). Pipeline statistics: `counters`.
  bool rayQuery = false;
  bool meshShaders = false;
  // A device that runs on the CPU (Vulkan: VK_PHYSICAL_DEVICE_TYPE_CPU, lavapipe; GL:
  // llvmpipe or softpipe): what is fast there differs from a GPU (rt's tier=auto).
  bool cpuDevice = false;
  bool timestamps = false;
  // The sample counts a texture may have, as a mask of the counts themselves
  // (bit value 4 = 4 samples, like VkSampleCountFlags): those every float and
  // unorm colour format and Depth32F support as render targets (GL:
  // glGetInternalformativ GL_SAMPLES of each; Vulkan: the framebuffer colour
  // and depth sample counts). Always has 1. Integer formats are never
  // multisampled.
  uint32_t sampleCounts = 1;
  // The most bytes one storage buffer may have where a shader can see all of
  // it (Vulkan: maxStorageBufferRange, 128 MiB on lavapipe; GL:
  // GL_MAX_SHADER_STORAGE_BLOCK_SIZE, 128 MiB on llvmpipe): a larger one would
  // be bound in part, so it is refused, and fragment pools that may grow past
  // it are split into pages (render/common/fragment_lists.h). 0: no limit.
  std::size_t maxStorageBufferBytes = 0;
};

// The memory a run may still take on a device, and where that figure came from
// (in messages). bytes 0: not known (no query the device answers).
struct MemoryBudget {
  std::size_t bytes = 0;
  std::string source;  // e.g. "VK_EXT_memory_budget", "host MemAvailable"
};

// The window's image as present() showed it, read back from the window's
// framebuffer (GL) or swapchain image (Vulkan): RGBA8, rows bottom-up like
// readTexture, the window's size.
struct PresentedImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba8;
};

class Window;
class Driver;
struct DriverObject;
struct DriverBinding;

// The one device front end. It owns the handle tables, the frame/pass state
// machine, every contract check and the memory accounting, once for both APIs;
// below it a narrow per-API Driver (backends/driver.h) records the work. A rule
// broken on one API is broken on both, with one message (DeviceError).
class Device {
 public:
  explicit Device(std::unique_ptr<Driver> driver);
  ~Device();
  Device(const Device&) = delete;
  Device& operator=(const Device&) = delete;

  DeviceInfo info() const;
  // The most colour targets a pass (PassDesc::color) or a pipeline
  // (PipelineDesc::colorFormats) may have on this device: techniques size
  // their passes by it (at least 4, the least Vulkan guarantees).
  uint32_t maxColorAttachments() const { return maxColorAttachments_; }
  // Whether textures and pipelines may have `samples` samples per pixel.
  bool supportsSamples(uint32_t samples) const;
  // The supported counts, in words ("1, 4"), for messages.
  std::string sampleCountsText() const;

  // A buffer of zero bytes is an error. Contents are zero unless data is given.
  Buffer createBuffer(const BufferDesc& desc, const void* data = nullptr);
  // Ray queries (DeviceInfo::rayQuery; a DeviceError elsewhere): an
  // acceleration structure over `boxes` axis-aligned boxes of the storage
  // buffer `aabbs`, 6 floats each (min xyz, max xyz; 24 bytes): a bottom level
  // of procedural geometry (a candidate's primitive index is its box's index)
  // under a top level of one identity instance, opaque flags off so that every
  // candidate reaches the shader. A buffer of usage AccelerationStructure, bound
  // to AccelerationStructure slots only (never updated, filled or read back).
  // Its bytes, known at once from the driver, are everything it holds: both
  // levels, the build's scratch and the copies of the boxes and the instance.
  // It is made, and built on the device, when first used, like any buffer,
  // from the boxes' contents at that moment: give them at creation or by
  // updateBuffer outside frames.
  Buffer createAccelerationStructure(const std::string& name, Owner owner, Buffer aabbs,
                                     uint32_t boxes);
  // Ordered with the recorded work: allowed between passes inside a frame.
  void updateBuffer(Buffer b, const void* data, std::size_t bytes, std::size_t offset = 0);
  void fillBuffer(Buffer b, uint32_t value);  // between passes
  // Contents are zero (colour) or 1 (depth) until first written.
  Texture createTexture(const TextureDesc& desc);
  Pipeline createPipeline(const PipelineDesc& desc);  // throws DeviceError
  // Why this device makes no mesh pipelines (PipelineDesc::mesh), or "" when it does.
  std::string meshPipelineRefusal() const;
  // While deferral is on, a pipeline created is checked at once but compiled
  // only by compilePipelines or when first drawn or dispatched: the renderer
  // declares every technique's pipelines, culls its frame graph, and compiles
  // those of the kept passes only (a culled technique compiles nothing).
  void setDeferPipelines(bool defer) { deferPipelines_ = defer; }
  // Compiles the deferred pipelines among these ids (throws DeviceError).
  void compilePipelines(const std::set<uint32_t>& ids);
  // A group's pipelines that were compiled (name, technique), in creation order.
  std::vector<std::pair<std::string, std::string>> compiledPipelines(uint32_t group) const;
  // While on, a buffer created with data keeps a copy of it and is made, like
  // any other, when first used or by makeDeferredBuffers(): the renderer
  // declares everything, scene included, and asks the memory guard about its
  // whole plan before anything is made.
  void setDeferMaking(bool defer) { deferMaking_ = defer; }
  void makeDeferredBuffers();
  // A null handle is ignored; an unknown one is an error.
  void destroy(Buffer b);
  void destroy(Texture t);
  void destroy(Pipeline p);

  // Resource groups (ResourceGroup, GroupScope below): every buffer, texture
  // and pipeline created while a group is current belongs to it, and
  // destroyGroup frees them all. Techniques create and never destroy; the
  // renderer that made them owns a group, so replacing it frees what it made.
  uint32_t createGroup() { return nextGroup_++; }
  uint32_t currentGroup() const { return group_; }
  void setCurrentGroup(uint32_t group) { group_ = group; }
  // Inside an unfinished frame (a run stopped by an exception) nothing is
  // freed: what the frame recorded may still be in use, and a device left so
  // is destroyed, not reused.
  void destroyGroup(uint32_t group) noexcept;

  void beginFrame();
  void beginPass(const PassDesc& pass);
  // Every binding the pipeline declares must be given, of its kind, once; a
  // sampled texture must be listed in the pass's sampledTextures.
  void draw(Pipeline p, const std::vector<Binding>& bindings, uint32_t vertexCount,
            uint32_t instanceCount = 1);
  void endPass();
  // Compute work runs as its own timed pass (outside render passes).
  void dispatch(const std::string& passName, Pipeline p, const std::vector<Binding>& bindings,
                uint32_t x, uint32_t y = 1, uint32_t z = 1);
  void endFrame();  // submits, waits
  std::vector<PassTiming> lastFrameTimings() const;

  // Read back after endFrame(). Rows are bottom-up (row 0 = NDC y=-1);
  // tightly packed, bytesPerPixel(format) per pixel; the layers of an array
  // one after the other (layer 0 first).
  std::vector<uint8_t> readTexture(Texture t);
  std::vector<uint8_t> readBuffer(Buffer b);
  // The inverse of readTexture: the whole texture's contents, laid out as
  // readTexture returns them (bytes must be exactly that size). Outside frames.
  void writeTexture(Texture t, const std::vector<uint8_t>& bytes);

  // Window platforms only (DeviceOptions::platform "window"): the window (null
  // on headless platforms), and present(), which shows layer 0 of a colour
  // (not integer) texture in it, scaled to the window's size, upright (row 0
  // of the texture at the bottom), values clamped to [0,1] as in a PNG; it
  // waits until the image is handed to the window system. Outside frames.
  // With `capture`, the image shown is read back into it. Returns false, and
  // shows nothing, while the window is minimized (zero size). Resizes are
  // followed (the swapchain is recreated).
  Window* window();
  bool present(Texture t, PresentedImage* capture = nullptr);
  // What a texture or a buffer was created with (to interpret read-back bytes,
  // to name it in messages).
  TextureDesc describe(Texture t) const;
  BufferDesc describe(Buffer b) const;

  // Exact logical bytes (width*height*layers*bpp, buffer size) of every resource made
  // on the device, in creation order. A resource is made when first used (by a
  // pass, a binding, an update or a read), or at once when created with data.
  std::vector<ResourceBytes> allocations() const;
  // The same for every live resource declared, made or not.
  std::vector<ResourceBytes> declared() const;
  // Every live resource in creation order, made or only declared: what the
  // frame graph plans a frame's memory from (render/graph/frame_planner.h).
  struct Held {
    uint32_t id = 0;
    ResourceBytes bytes;
    bool made = false;
  };
  std::vector<Held> inventory() const;
  // Refuses (DeviceError) any storage buffer among these ids over
  // maxStorageBufferBytes, before it is made.
  void checkStorageRanges(const std::set<uint32_t>& ids) const;
  // Handle ids grow with creation: the ids of the live buffers and textures
  // created since nextHandleId() returned `first`.
  uint32_t nextHandleId() const { return nextId_; }
  std::set<uint32_t> resourceIdsFrom(uint32_t first) const;
  std::set<uint32_t> pipelineIdsFrom(uint32_t first) const;
  // A buffer declared and not made yet takes its size now (a list sized by a
  // counting pass in a preparation, declared before the frame graph is built).
  void setBufferSize(Buffer b, std::size_t bytes);

  // What the device can still give (Vulkan: VK_EXT_memory_budget, else the
  // device-local heap; GL: GL_NVX_gpu_memory_info or GL_ATI_meminfo; the CPU
  // drivers: host memory, hostMemoryBudget()). Asked once per run, before its
  // resources are made.
  MemoryBudget memoryBudget() const;

  // The one hook below the frame graph's planning (render/graph/frame_planner.h
  // installs it; the device owns it): the name a new resource or pass takes
  // (an extra light's prefix), a resource about to be made (the memory guard:
  // it throws to refuse) and a pass about to be recorded (beginPass, dispatch:
  // what it throws leaves the device to be destroyed, not reused).
  class Hook {
   public:
    virtual ~Hook() = default;
    virtual std::string label(const std::string& name) const = 0;
    virtual void beforeMaking(const ResourceBytes& resource) = 0;
    virtual void beforePass(const std::string& pass) = 0;
  };
  void setHook(std::unique_ptr<Hook> hook) { hook_ = std::move(hook); }
  Hook* hook() const { return hook_.get(); }

 private:
  struct BufferRec;
  struct TextureRec;
  struct PipelineRec;
  struct OpenPass;
  BufferRec& buffer(Buffer b, const std::string& where);
  const BufferRec& buffer(Buffer b, const std::string& where) const;
  TextureRec& texture(Texture t, const std::string& where);
  const TextureRec& texture(Texture t, const std::string& where) const;
  PipelineRec& pipeline(Pipeline p, const std::string& where);
  void requireFrame(const std::string& where, bool inFrame, bool inPass) const;
  template <class Table>
  void destroyIn(Table& table, uint32_t id, const char* kind);
  DriverObject* created(BufferRec& r);
  DriverObject* created(TextureRec& t);
  std::vector<ResourceBytes> resources(bool createdOnly) const;
  // Counts what it binds in `counted` (the open pass, or a dispatch's own).
  std::vector<DriverBinding> resolve(const PipelineRec& p, const std::vector<Binding>& given,
                                     const std::string& where, bool inPass, OpenPass& counted);

  std::unique_ptr<Driver> driver_;
  uint32_t maxColorAttachments_ = 0;
  uint32_t sampleCounts_ = 1;
  uint32_t nextId_ = 1;  // shared by all kinds: ids give creation order
  std::map<uint32_t, std::unique_ptr<BufferRec>> buffers_;
  std::map<uint32_t, std::unique_ptr<TextureRec>> textures_;
  std::map<uint32_t, std::unique_ptr<PipelineRec>> pipelines_;
  bool inFrame_ = false, inPass_ = false;
  std::unique_ptr<OpenPass> pass_;
  std::vector<PassWork> frameWork_;      // the open frame's passes, in order
  std::vector<PassTiming> lastTimings_;  // the last frame's, with their work
  std::unique_ptr<Hook> hook_;
  uint32_t nextGroup_ = 1, group_ = 0;
  bool deferPipelines_ = false;
  bool deferMaking_ = false;
  DriverObject* compiled(PipelineRec& p);
  std::string labelled(const std::string& name) const { return hook_ ? hook_->label(name) : name; }
  void guardMaking(const std::string& name, Owner owner, std::size_t bytes) const;
  void checkStorageRange(const BufferDesc& desc) const;
  void requireContents(const BufferRec& r, const char* call) const;
};

struct DeviceOptions {
  std::string backend = "gl";    // gl | vulkan
  std::string platform = "egl";  // gl: egl | osmesa | window; vulkan: headless | window
  bool validation = false;       // Vulkan validation layers; messages counted
  // Window platforms: the window's first size and title.
  uint32_t windowWidth = 512, windowHeight = 512;
  std::string windowTitle = "strandbench";
};

// Throws DeviceError with a clear message when the backend is unavailable.
std::unique_ptr<Device> createDevice(const DeviceOptions& opts);

// The host memory this process can still take: /proc/meminfo's MemAvailable,
// and under an address-space limit (RLIMIT_AS) what is left of it. The budget
// of the CPU drivers (llvmpipe, lavapipe), whose device memory is host memory.
MemoryBudget hostMemoryBudget();

// Validation messages seen by Vulkan devices in this process (0 for GL).
std::size_t validationMessageCount();

// Owns what is created on a device while it is current (GroupScope) and
// destroys it all when it goes (Device::destroyGroup).
class ResourceGroup {
 public:
  explicit ResourceGroup(Device& dev) : dev_(dev), id_(dev.createGroup()) {}
  ~ResourceGroup() { dev_.destroyGroup(id_); }
  ResourceGroup(const ResourceGroup&) = delete;
  ResourceGroup& operator=(const ResourceGroup&) = delete;
  uint32_t id() const { return id_; }

 private:
  Device& dev_;
  uint32_t id_;
};

// Makes a group current for the lifetime of the scope, then the previous one again.
class GroupScope {
 public:
  GroupScope(Device& dev, const ResourceGroup& group) : dev_(dev), previous_(dev.currentGroup()) {
    dev_.setCurrentGroup(group.id());
  }
  ~GroupScope() { dev_.setCurrentGroup(previous_); }
  GroupScope(const GroupScope&) = delete;
  GroupScope& operator=(const GroupScope&) = delete;

 private:
  Device& dev_;
  uint32_t previous_;
};

}  // namespace sb
