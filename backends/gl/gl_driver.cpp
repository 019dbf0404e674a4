// The driver under the Device front end on OpenGL 4.5 core (direct state access).
#include "backends/gl/gl_driver.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iterator>
#include <map>
#include <string>
#include <vector>

#include "backends/gl/gl_functions.h"
#include "backends/gl/gl_platform.h"
#include "backends/shader_source.h"
#include "backends/window.h"

namespace sb {
namespace {

struct GLFormat {
  GLenum internal, format, type;
};

// Tables in the order of the enums in backends/device.h.
constexpr GLFormat kFormats[] = {{GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE},
                                 {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT},
                                 {GL_RGBA32F, GL_RGBA, GL_FLOAT},
                                 {GL_R32F, GL_RED, GL_FLOAT},
                                 {GL_RG32F, GL_RG, GL_FLOAT},
                                 {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT},
                                 {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT},
                                 {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT}};
static_assert(std::size(kFormats) == std::size_t(Format::Depth32F) + 1);
constexpr GLenum kCompare[] = {GL_NEVER,   GL_LESS,   GL_LEQUAL,   GL_EQUAL,
                               GL_GREATER, GL_GEQUAL, GL_NOTEQUAL, GL_ALWAYS};
static_assert(std::size(kCompare) == std::size_t(CompareOp::Always) + 1);
constexpr GLenum kBlendFactors[] = {GL_ZERO,      GL_ONE,
                                    GL_SRC_COLOR, GL_ONE_MINUS_SRC_COLOR,
                                    GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA,
                                    GL_DST_COLOR, GL_ONE_MINUS_DST_COLOR,
                                    GL_DST_ALPHA, GL_ONE_MINUS_DST_ALPHA};
static_assert(std::size(kBlendFactors) == std::size_t(BlendFactor::OneMinusDstAlpha) + 1);
constexpr GLenum kBlendOps[] = {GL_FUNC_ADD, GL_FUNC_SUBTRACT, GL_FUNC_REVERSE_SUBTRACT, GL_MIN,
                                GL_MAX};
static_assert(std::size(kBlendOps) == std::size_t(BlendOp::Max) + 1);

GLFormat glFormat(Format f) { return byEnum(kFormats, f); }
GLenum glCompare(CompareOp op) { return byEnum(kCompare, op); }
GLenum glBlendFactor(BlendFactor f) { return byEnum(kBlendFactors, f); }
GLenum glBlendOp(BlendOp op) { return byEnum(kBlendOps, op); }

const char* glErrorName(GLenum e) {
  switch (e) {
    case GL_INVALID_ENUM:
      return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE:
      return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION:
      return "GL_INVALID_OPERATION";
    case GL_OUT_OF_MEMORY:
      return "GL_OUT_OF_MEMORY";
    case GL_INVALID_FRAMEBUFFER_OPERATION:
      return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default:
      return "GL error";
  }
}

using Clock = std::chrono::steady_clock;
bool envSet(const char* name) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' && std::string(v) != "0";
}
double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

struct GLBuffer : DriverObject {
  GLuint name = 0;
};
struct GLTexture : DriverObject {
  GLuint name = 0;  // GL_TEXTURE_2D, GL_TEXTURE_2D_ARRAY with layers > 1, or
                    // GL_TEXTURE_2D_MULTISAMPLE with samples > 1
  uint32_t layers = 1;
  GLuint arrayView = 0;  // layers == 1: a GL_TEXTURE_2D_ARRAY view, made when first needed
};
struct GLPipeline : DriverObject {
  GLuint program = 0;
};
GLuint nameOf(const DriverObject* o) {
  if (auto* b = dynamic_cast<const GLBuffer*>(o)) return b->name;
  return static_cast<const GLTexture*>(o)->name;
}

class GLDriver final : public Driver {
 public:
  explicit GLDriver(std::unique_ptr<GLPlatform> platform) : platform_(std::move(platform)) {
#define SB_GL_LOAD(type, fn)                                            \
  gl_.fn = reinterpret_cast<type>(platform_->getProcAddress("gl" #fn)); \
  if (!gl_.fn)                                                          \
    throw DeviceError("GL (" + platform_->name() + "): missing gl" #fn " (need OpenGL 4.5 core)");
    SB_GL_FUNCTIONS(SB_GL_LOAD)
#undef SB_GL_LOAD
    GLint major = 0, minor = 0;
    gl_.GetIntegerv(GL_MAJOR_VERSION, &major);
    gl_.GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 45)
      throw DeviceError("GL (" + platform_->name() + "): OpenGL 4.5 needed, context is " +
                        std::to_string(major) + "." + std::to_string(minor));
    info_.backend = "gl";
    info_.platform = platform_->name();
    info_.device = reinterpret_cast<const char*>(gl_.GetString(GL_RENDERER));
    info_.driver = reinterpret_cast<const char*>(gl_.GetString(GL_VERSION));
    info_.apiVersion = std::to_string(major) + "." + std::to_string(minor);
    info_.timestamps = true;  // glQueryCounter: core since 3.3
    // Timing: GPU timestamps (glQueryCounter at each pass's start and end, no finish
    // between passes) on GPUs; on llvmpipe the CPU clock around each pass, since its
    // timer queries miss vertex work. SB_GL_GPU_TIMING=1 / SB_GL_CPU_TIMING=1 force one.
    const std::string renderer = info_.device;
    info_.cpuDevice = renderer.find("llvmpipe") != std::string::npos ||
                      renderer.find("softpipe") != std::string::npos;
    gpuTiming_ = !envSet("SB_GL_CPU_TIMING") && (!info_.cpuDevice || envSet("SB_GL_GPU_TIMING"));
    info_.timing = gpuTiming_ ? "gpu timestamps (glQueryCounter)"
                              : "cpu clock per pass (glFinish before and after)";
    info_.lines = "aliased (diamond exit)";
    info_.present = platform_->presentMode();
    // Draw buffers and framebuffer attachments both bound a pass's targets.
    GLint drawBuffers = 0, colorAttachments = 0;
    gl_.GetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    gl_.GetIntegerv(GL_MAX_COLOR_ATTACHMENTS, &colorAttachments);
    info_.maxColorAttachments =
        static_cast<uint32_t>(std::max(0, std::min(drawBuffers, colorAttachments)));
    // The largest shader storage block, as Vulkan's maxStorageBufferRange
    // (128 MiB on llvmpipe): larger pools are split into pages below it.
    GLint64 storageBlock = 0;
    gl_.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &storageBlock);
    info_.maxStorageBufferBytes = static_cast<std::size_t>(std::max<GLint64>(0, storageBlock));
    GLint extensions = 0;
    gl_.GetIntegerv(GL_NUM_EXTENSIONS, &extensions);
    for (GLint i = 0; i < extensions; ++i) {
      const char* e = reinterpret_cast<const char*>(gl_.GetStringi(GL_EXTENSIONS, GLuint(i)));
      if (e && std::strcmp(e, "GL_ARB_fragment_shader_interlock") == 0)
        info_.fragmentShaderInterlock = true;
      if (e && std::strcmp(e, "GL_ARB_pipeline_statistics_query") == 0) statistics_ = true;
      if (e &&
          (std::strcmp(e, "GL_EXT_mesh_shader") == 0 || std::strcmp(e, "GL_NV_mesh_shader") == 0))
        info_.meshShaders = true;
    }
    statistics_ = statistics_ || major * 10 + minor >= 46;  // core in 4.6
    info_.counters = statistics_ ? "ARB_pipeline_statistics_query, GL_SAMPLES_PASSED" : "";
    info_.sampleCounts = multisampleCounts();
    // Same conventions as Vulkan: NDC y=-1 at row 0, depth in [0,1].
    gl_.ClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    gl_.CreateVertexArrays(1, &vao_);  // core profile needs one bound, even if empty
    gl_.BindVertexArray(vao_);
    gl_.Disable(GL_CULL_FACE);
    gl_.Disable(GL_MULTISAMPLE);
    gl_.Disable(GL_LINE_SMOOTH);
    gl_.Disable(GL_DITHER);
    gl_.LineWidth(1.0f);
    gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
    gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    checkError("context setup");
  }

  ~GLDriver() override {
    platform_->makeCurrent();  // its objects, whichever device was used last
    if (!queries_.empty()) gl_.DeleteQueries(GLsizei(queries_.size()), queries_.data());
    for (auto& q : counterQueries_) gl_.DeleteQueries(GLsizei(q.size()), q.data());
    for (auto& [key, fbo] : fbos_) gl_.DeleteFramebuffers(1, &fbo);
    if (presentFbo_) gl_.DeleteFramebuffers(1, &presentFbo_);
    gl_.DeleteVertexArrays(1, &vao_);
  }

  DeviceInfo info() const override { return info_; }

  MemoryBudget memoryBudget() const override {
    // The vendors' memory-info extensions (NVIDIA, AMD) report free video
    // memory in KiB; Mesa's CPU rasterizers keep textures in host memory.
    constexpr GLenum kNvxAvailableKiB = 0x9049;    // GPU_MEMORY_INFO_CURRENT_AVAILABLE_VIDMEM_NVX
    constexpr GLenum kAtiTextureFreeKiB = 0x87FC;  // TEXTURE_FREE_MEMORY_ATI: 4 values, [0] free
    GLint count = 0;
    gl_.GetIntegerv(GL_NUM_EXTENSIONS, &count);
    bool nvx = false, ati = false;
    for (GLint i = 0; i < count; ++i) {
      const char* e = reinterpret_cast<const char*>(gl_.GetStringi(GL_EXTENSIONS, GLuint(i)));
      if (!e) continue;
      nvx = nvx || std::strcmp(e, "GL_NVX_gpu_memory_info") == 0;
      ati = ati || std::strcmp(e, "GL_ATI_meminfo") == 0;
    }
    GLint kib[4] = {0, 0, 0, 0};
    if (nvx) {
      gl_.GetIntegerv(kNvxAvailableKiB, kib);
      if (kib[0] > 0) return {std::size_t(kib[0]) * 1024, "GL_NVX_gpu_memory_info"};
    }
    if (ati) {
      gl_.GetIntegerv(kAtiTextureFreeKiB, kib);
      if (kib[0] > 0) return {std::size_t(kib[0]) * 1024, "GL_ATI_meminfo"};
    }
    gl_.GetError();  // a query the context did not take leaves no error behind
    if (info_.cpuDevice) return hostMemoryBudget();
    return {};
  }

  std::unique_ptr<DriverObject> createBuffer(const BufferDesc& desc, const void* data) override {
    auto b = std::make_unique<GLBuffer>();
    gl_.CreateBuffers(1, &b->name);
    gl_.NamedBufferStorage(b->name, static_cast<GLsizeiptr>(desc.bytes), data,
                           GL_DYNAMIC_STORAGE_BIT);
    if (!data) {  // a fresh store is zero-filled, as on Vulkan
      const uint8_t zero = 0;
      gl_.ClearNamedBufferData(b->name, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, &zero);
    }
    checkError("createBuffer " + desc.name);
    return b;
  }

  std::unique_ptr<DriverObject> createTexture(const TextureDesc& desc) override {
    auto t = std::make_unique<GLTexture>();
    const GLFormat f = glFormat(desc.format);
    t->layers = desc.layers;
    if (desc.samples > 1) {
      // Fixed sample locations: the same pattern in every pixel, as Vulkan's
      // standard sample locations. Sampler state does not apply (never sampled).
      gl_.CreateTextures(GL_TEXTURE_2D_MULTISAMPLE, 1, &t->name);
      gl_.TextureStorage2DMultisample(t->name, static_cast<GLsizei>(desc.samples), f.internal,
                                      static_cast<GLsizei>(desc.width),
                                      static_cast<GLsizei>(desc.height), GL_TRUE);
      clearMultisampled(t->name, desc);
      checkError("createTexture " + desc.name);
      return t;
    }
    if (desc.layers > 1) {
      gl_.CreateTextures(GL_TEXTURE_2D_ARRAY, 1, &t->name);
      gl_.TextureStorage3D(t->name, 1, f.internal, static_cast<GLsizei>(desc.width),
                           static_cast<GLsizei>(desc.height), static_cast<GLsizei>(desc.layers));
    } else {
      gl_.CreateTextures(GL_TEXTURE_2D, 1, &t->name);
      gl_.TextureStorage2D(t->name, 1, f.internal, static_cast<GLsizei>(desc.width),
                           static_cast<GLsizei>(desc.height));
    }
    samplerState(t->name, desc);
    // Defined initial contents, as on Vulkan: colour 0, depth 1 (far).
    const float depthOne = 1.0f;
    const uint32_t zero[4] = {0, 0, 0, 0};
    if (isDepthFormat(desc.format))
      gl_.ClearTexImage(t->name, 0, f.format, f.type, &depthOne);
    else
      gl_.ClearTexImage(t->name, 0, f.format, f.type, zero);
    checkError("createTexture " + desc.name);
    return t;
  }

  std::unique_ptr<DriverObject> createPipeline(const PipelineDesc& desc) override {
    auto p = std::make_unique<GLPipeline>();
    p->program = gl_.CreateProgram();
    std::vector<GLuint> shaders;
    auto addStage = [&](const ShaderCode* code, GLenum stage) {
      if (!code) return;
      const std::string src = completeShaderSource(*code, ShaderApi::GL);
      GLuint s = gl_.CreateShader(stage);
      const char* text = src.c_str();
      gl_.ShaderSource(s, 1, &text, nullptr);
      gl_.CompileShader(s);
      GLint ok = 0;
      gl_.GetShaderiv(s, GL_COMPILE_STATUS, &ok);
      if (!ok) {
        std::string log = shaderLog(s, false);
        gl_.DeleteShader(s);
        for (GLuint x : shaders) gl_.DeleteShader(x);
        gl_.DeleteProgram(p->program);
        throw DeviceError(describeCompileError(*code, desc.technique, log));
      }
      gl_.AttachShader(p->program, s);
      shaders.push_back(s);
    };
    addStage(desc.vertex, GL_VERTEX_SHADER);
    addStage(desc.fragment, GL_FRAGMENT_SHADER);
    addStage(desc.compute, GL_COMPUTE_SHADER);
    gl_.LinkProgram(p->program);
    for (GLuint s : shaders) gl_.DeleteShader(s);
    GLint ok = 0;
    gl_.GetProgramiv(p->program, GL_LINK_STATUS, &ok);
    if (!ok) {
      std::string log = shaderLog(p->program, true);
      gl_.DeleteProgram(p->program);
      throw DeviceError("shader link error in pipeline '" + desc.name + "' (technique '" +
                        desc.technique + "'):\n" + log);
    }
    return p;
  }

  void release(std::unique_ptr<DriverObject> object) override {
    // GL orders deletion after the work that uses an object: free at once.
    if (auto* p = dynamic_cast<GLPipeline*>(object.get())) {
      gl_.DeleteProgram(p->program);
    } else if (auto* b = dynamic_cast<GLBuffer*>(object.get())) {
      gl_.DeleteBuffers(1, &b->name);
    } else if (auto* t = dynamic_cast<GLTexture*>(object.get())) {
      // Framebuffers that used it are dropped too.
      const std::string needle = "," + std::to_string(t->name) + ",";
      for (auto f = fbos_.begin(); f != fbos_.end();) {
        if (f->first.find(needle) != std::string::npos) {
          gl_.DeleteFramebuffers(1, &f->second);
          f = fbos_.erase(f);
        } else {
          ++f;
        }
      }
      if (t->arrayView) gl_.DeleteTextures(1, &t->arrayView);
      gl_.DeleteTextures(1, &t->name);
    }
  }

  void updateBuffer(DriverObject& b, const BufferDesc& desc, const void* data, std::size_t bytes,
                    std::size_t offset) override {
    gl_.NamedBufferSubData(nameOf(&b), static_cast<GLintptr>(offset),
                           static_cast<GLsizeiptr>(bytes), data);
    checkError("updateBuffer " + desc.name);
  }

  void fillBuffer(DriverObject& b, const BufferDesc& desc, uint32_t value) override {
    gl_.ClearNamedBufferData(nameOf(&b), GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
    checkError("fillBuffer " + desc.name);
  }

  void beginFrame() override {
    timings_.clear();
    stampNames_.clear();
    counted_.clear();
    gl_.Finish();  // earlier uploads do not count against the first pass
    frameStart_ = Clock::now();
  }

  // GPU timing: a timestamp query written now, after the commands before it.
  void stamp(std::size_t i) {
    if (i >= queries_.size()) {
      const std::size_t more = std::max<std::size_t>(64, queries_.size());
      queries_.resize(queries_.size() + more);
      gl_.CreateQueries(GL_TIMESTAMP, GLsizei(more), queries_.data() + queries_.size() - more);
    }
    gl_.QueryCounter(queries_[i], GL_TIMESTAMP);
  }
  void beginTiming(const std::string& name) {
    if (!gpuTiming_) {
      gl_.Finish();
      passStart_ = Clock::now();
      return;
    }
    stamp(2 * stampNames_.size());  // pass p: queries 2p (start) and 2p + 1 (end)
    stampNames_.push_back(name);
  }
  void endTiming(const std::string& name) {
    if (!gpuTiming_) {
      gl_.Finish();  // GL timer queries on llvmpipe miss vertex work: time with the CPU
      const auto end = Clock::now();
      timings_.push_back({name, msBetween(passStart_, end), msBetween(frameStart_, passStart_)});
      return;
    }
    stamp(2 * stampNames_.size() - 1);
  }

  // The work counters: one query of each target per pass (reused per frame),
  // begun after the pass's clears and ended before its resolves, so that
  // neither counts (Vulkan's happen outside the queries too).
  void beginCounting(bool graphics) {
    if (!statistics_) return;
    const std::size_t i = counted_.size();
    if (i == counterQueries_.size()) {
      // glGenQueries: Mesa 22.3's glCreateQueries refuses the statistics
      // targets (GL_INVALID_ENUM); a name gets its target at its first begin.
      counterQueries_.emplace_back();
      gl_.GenQueries(GLsizei(kCounterTargets.size()), counterQueries_[i].data());
    }
    counted_.push_back(graphics);
    for (std::size_t t = 0; t < kCounterTargets.size(); ++t)
      if (graphics || kCounterTargets[t] != GL_SAMPLES_PASSED)
        gl_.BeginQuery(kCounterTargets[t], counterQueries_[i][t]);
  }
  void endCounting() {
    if (!statistics_) return;
    for (GLenum target : kCounterTargets)
      if (counted_.back() || target != GL_SAMPLES_PASSED) gl_.EndQuery(target);
  }
  // After the frame's finish: each pass's counts into its timing.
  void readCounts() {
    for (std::size_t p = 0; p < counted_.size() && p < timings_.size(); ++p) {
      ApiCounts v{};
      for (std::size_t t = 0; t < v.size(); ++t)
        if (counted_[p] || kCounterTargets[t] != GL_SAMPLES_PASSED)
          gl_.GetQueryObjectui64v(counterQueries_[p][t], GL_QUERY_RESULT, &v[t]);
      setApiCounts(timings_[p].work, v);
    }
  }

  void beginPass(const DriverPass& pass) override {
    passName_ = pass.name;
    // Storage writes of earlier passes become visible (the Vulkan driver puts
    // a full barrier here too).
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    const GLuint fbo = framebuffer(pass);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    gl_.Viewport(0, 0, static_cast<GLsizei>(pass.width), static_cast<GLsizei>(pass.height));
    // Multisampled rasterization (per-sample coverage, depth and
    // gl_SampleMask) only in multisampled passes; elsewhere GL_MULTISAMPLE
    // stays off, as set up, so single-sampled passes rasterize as before.
    passSamples_ = pass.samples;
    if (pass.samples > 1)
      gl_.Enable(GL_MULTISAMPLE);
    else
      gl_.Disable(GL_MULTISAMPLE);
    resolves_.clear();
    for (std::size_t i = 0; i < pass.color.size(); ++i)
      if (pass.color[i].resolve.object) resolves_.push_back({fbo, i, pass.color[i], pass});
    beginTiming(pass.name);
    for (std::size_t i = 0; i < pass.color.size(); ++i) {
      const auto& a = pass.color[i];
      if (a.load != LoadOp::Clear) continue;
      gl_.ColorMaski(static_cast<GLuint>(i), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      if (isIntegerFormat(a.texture.desc->format))
        gl_.ClearNamedFramebufferuiv(fbo, GL_COLOR, static_cast<GLint>(i), a.clearUint.data());
      else
        gl_.ClearNamedFramebufferfv(fbo, GL_COLOR, static_cast<GLint>(i), a.clear.data());
    }
    if (pass.depth.object && pass.depthLoad == LoadOp::Clear) {
      gl_.DepthMask(GL_TRUE);
      gl_.ClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &pass.depthClear);
    }
    beginCounting(true);
  }

  void draw(DriverObject& pipeline, const PipelineDesc& desc,
            const std::vector<DriverBinding>& bindings, uint32_t vertexCount,
            uint32_t instanceCount) override {
    gl_.UseProgram(static_cast<GLPipeline&>(pipeline).program);
    applyState(desc);
    bind(bindings);
    // Lines in a multisampled pass: Vulkan's Bresenham lines cover every sample
    // of the pixels they cover (at the pixel centre), where GL's multisampled
    // lines are rectangles covering samples one by one. Aliased lines
    // (multisample rasterization off) match Vulkan's; llvmpipe still applies
    // gl_SampleMask to them (measured: tests/test_oit_peeling.cpp).
    if (passSamples_ > 1) {
      if (desc.topology == Topology::Lines)
        gl_.Disable(GL_MULTISAMPLE);
      else
        gl_.Enable(GL_MULTISAMPLE);
    }
    gl_.DrawArraysInstanced(desc.topology == Topology::Lines ? GL_LINES : GL_TRIANGLES, 0,
                            static_cast<GLsizei>(vertexCount), static_cast<GLsizei>(instanceCount));
  }

  void endPass() override {
    endCounting();
    // Resolves, part of the pass (Vulkan's happen at the end of rendering):
    // a blit from each multisampled attachment averages its samples.
    for (const Resolve& r : resolves_) {
      const GLuint to = resolveFramebuffer(r.target.resolve);
      gl_.NamedFramebufferReadBuffer(r.fbo, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(r.index));
      const GLint w = GLint(r.width), h = GLint(r.height);
      gl_.BlitNamedFramebuffer(r.fbo, to, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    }
    resolves_.clear();
    endTiming(passName_);
    checkError("pass " + passName_);
  }

  void dispatch(const std::string& passName, DriverObject& pipeline, const PipelineDesc&,
                const std::vector<DriverBinding>& bindings, uint32_t x, uint32_t y,
                uint32_t z) override {
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    beginTiming(passName);
    gl_.UseProgram(static_cast<GLPipeline&>(pipeline).program);
    bind(bindings);
    beginCounting(false);
    gl_.DispatchCompute(x, y, z);
    endCounting();
    endTiming(passName);
    checkError("dispatch " + passName);
  }

  void endFrame() override {
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.Finish();
    if (gpuTiming_ && !stampNames_.empty()) {
      // Each pass's start and end stamps, in nanoseconds, from the frame's first stamp.
      std::vector<GLuint64> ns(2 * stampNames_.size());
      for (std::size_t i = 0; i < ns.size(); ++i)
        gl_.GetQueryObjectui64v(queries_[i], GL_QUERY_RESULT, &ns[i]);
      for (std::size_t p = 0; p < stampNames_.size(); ++p)
        timings_.push_back({stampNames_[p], double(ns[2 * p + 1] - ns[2 * p]) / 1e6,
                            double(ns[2 * p] - ns[0]) / 1e6});
    }
    readCounts();
    checkError("endFrame");
  }

  std::vector<PassTiming> lastFrameTimings() const override { return timings_; }

  std::vector<uint8_t> readTexture(DriverObject& t, const TextureDesc& desc) override {
    const GLFormat f = glFormat(desc.format);
    // An array's level 0 holds every layer, layer after layer.
    std::vector<uint8_t> out(std::size_t{desc.width} * desc.height * desc.layers *
                             bytesPerPixel(desc.format));
    gl_.GetTextureImage(nameOf(&t), 0, f.format, f.type, static_cast<GLsizei>(out.size()),
                        out.data());
    checkError("readTexture " + desc.name);
    return out;
  }

  std::vector<uint8_t> readBuffer(DriverObject& b, const BufferDesc& desc) override {
    std::vector<uint8_t> out(desc.bytes);
    gl_.GetNamedBufferSubData(nameOf(&b), 0, static_cast<GLsizeiptr>(out.size()), out.data());
    checkError("readBuffer " + desc.name);
    return out;
  }

  void writeTexture(DriverObject& t, const TextureDesc& desc,
                    const std::vector<uint8_t>& bytes) override {
    const GLFormat f = glFormat(desc.format);
    const auto& tex = static_cast<const GLTexture&>(t);
    if (tex.layers > 1)
      gl_.TextureSubImage3D(tex.name, 0, 0, 0, 0, GLsizei(desc.width), GLsizei(desc.height),
                            GLsizei(desc.layers), f.format, f.type, bytes.data());
    else
      gl_.TextureSubImage2D(tex.name, 0, 0, 0, GLsizei(desc.width), GLsizei(desc.height), f.format,
                            f.type, bytes.data());
    checkError("writeTexture " + desc.name);
  }

  Window* window() override { return platform_->window(); }

  bool present(DriverObject& t, const TextureDesc& desc, PresentedImage* capture) override {
    Window* w = platform_->window();
    const GLint ww = static_cast<GLint>(w->width()), wh = static_cast<GLint>(w->height());
    if (ww == 0 || wh == 0) return false;  // minimized
    if (!presentFbo_) gl_.CreateFramebuffers(1, &presentFbo_);
    if (ww != presentWidth_ || wh != presentHeight_) {
      // A viewport call on the default framebuffer makes Mesa fetch the
      // window's buffers at their new size; without it the first blit after a
      // resize went to the old-size back buffer (measured on llvmpipe).
      gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
      gl_.Viewport(0, 0, ww, wh);
      presentWidth_ = ww;
      presentHeight_ = wh;
    }
    gl_.NamedFramebufferTexture(presentFbo_, GL_COLOR_ATTACHMENT0, nameOf(&t), 0);
    gl_.NamedFramebufferReadBuffer(presentFbo_, GL_COLOR_ATTACHMENT0);
    // Both have row 0 at the bottom: no flip. Float to the window's RGBA8
    // clamps and rounds, as the PNG writer does.
    const bool same = GLint(desc.width) == ww && GLint(desc.height) == wh;
    gl_.BlitNamedFramebuffer(presentFbo_, 0, 0, 0, GLint(desc.width), GLint(desc.height), 0, 0, ww,
                             wh, GL_COLOR_BUFFER_BIT, same ? GL_NEAREST : GL_LINEAR);
    if (capture) {  // the back buffer, before the swap leaves it undefined
      gl_.BindFramebuffer(GL_READ_FRAMEBUFFER, 0);
      gl_.NamedFramebufferReadBuffer(0, GL_BACK);
      capture->width = static_cast<uint32_t>(ww);
      capture->height = static_cast<uint32_t>(wh);
      capture->rgba8.assign(std::size_t(ww) * std::size_t(wh) * 4, 0);
      gl_.ReadPixels(0, 0, ww, wh, GL_RGBA, GL_UNSIGNED_BYTE, capture->rgba8.data());
    }
    platform_->swapBuffers();
    gl_.Finish();
    checkError("present " + desc.name);
    return true;
  }

 private:
  std::string shaderLog(GLuint obj, bool program) {
    GLint len = 0;
    if (program)
      gl_.GetProgramiv(obj, GL_INFO_LOG_LENGTH, &len);
    else
      gl_.GetShaderiv(obj, GL_INFO_LOG_LENGTH, &len);
    std::string log(static_cast<std::size_t>(len > 0 ? len : 1), '\0');
    if (program)
      gl_.GetProgramInfoLog(obj, len, nullptr, log.data());
    else
      gl_.GetShaderInfoLog(obj, len, nullptr, log.data());
    return log.c_str();
  }

  // The counts every float/unorm colour format and Depth32F take as
  // multisampled textures (glGetInternalformativ lists the exact counts).
  uint32_t multisampleCounts() {
    uint32_t mask = ~0u;
    for (std::size_t i = 0; i < std::size(kFormats); ++i) {
      const Format f = static_cast<Format>(i);
      if (isIntegerFormat(f)) continue;
      GLint n = 0;
      gl_.GetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, kFormats[i].internal, GL_NUM_SAMPLE_COUNTS,
                              1, &n);
      std::vector<GLint> counts(static_cast<std::size_t>(std::max(n, 0)));
      if (n > 0)
        gl_.GetInternalformativ(GL_TEXTURE_2D_MULTISAMPLE, kFormats[i].internal, GL_SAMPLES, n,
                                counts.data());
      uint32_t m = 0;
      for (GLint c : counts)
        if (c > 1 && c <= 64) m |= uint32_t(c);
      mask &= m;
    }
    gl_.GetError();
    return mask | 1u;
  }

  // A multisampled texture's defined first contents (colour 0, depth 1),
  // cleared through a framebuffer of its own.
  void clearMultisampled(GLuint name, const TextureDesc& desc) {
    GLuint fbo = 0;
    gl_.CreateFramebuffers(1, &fbo);
    const bool depth = isDepthFormat(desc.format);
    gl_.NamedFramebufferTexture(fbo, depth ? GL_DEPTH_ATTACHMENT : GL_COLOR_ATTACHMENT0, name, 0);
    if (depth) {
      const float one = 1.0f;
      gl_.DepthMask(GL_TRUE);
      gl_.ClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &one);
    } else {
      const GLenum at = GL_COLOR_ATTACHMENT0;
      gl_.NamedFramebufferDrawBuffers(fbo, 1, &at);
      const float zero[4] = {0, 0, 0, 0};
      gl_.ColorMaski(0, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      gl_.ClearNamedFramebufferfv(fbo, GL_COLOR, 0, zero);
    }
    gl_.DeleteFramebuffers(1, &fbo);
  }

  // The framebuffer a resolve blits into: the target alone, kept for reuse.
  GLuint resolveFramebuffer(const DriverTexture& target) {
    const std::string key = ",resolve," + std::to_string(nameOf(target.object)) + ",";
    auto it = fbos_.find(key);
    if (it != fbos_.end()) return it->second;
    GLuint fbo = 0;
    gl_.CreateFramebuffers(1, &fbo);
    gl_.NamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, nameOf(target.object), 0);
    const GLenum at = GL_COLOR_ATTACHMENT0;
    gl_.NamedFramebufferDrawBuffers(fbo, 1, &at);
    fbos_[key] = fbo;
    return fbo;
  }

  void checkError(const std::string& what) {
    GLenum e = gl_.GetError();
    if (e == GL_OUT_OF_MEMORY) throw OutOfMemoryError("GL_OUT_OF_MEMORY in " + what);
    if (e != GL_NO_ERROR) throw DeviceError(std::string(glErrorName(e)) + " in " + what);
  }

  void samplerState(GLuint name, const TextureDesc& desc) {
    const GLint filter =
        desc.linearFilter && !isIntegerFormat(desc.format) ? GL_LINEAR : GL_NEAREST;
    gl_.TextureParameteri(name, GL_TEXTURE_MIN_FILTER, filter);
    gl_.TextureParameteri(name, GL_TEXTURE_MAG_FILTER, filter);
    gl_.TextureParameteri(name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TextureParameteri(name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }

  // What a sampler2DArray samples: the array itself, or a one-layer
  // texture's GL_TEXTURE_2D_ARRAY view (a GL_TEXTURE_2D cannot be).
  GLuint arrayName(const DriverBinding& b) {
    auto& t = *static_cast<GLTexture*>(b.object);
    if (t.layers > 1) return t.name;
    if (!t.arrayView) {
      gl_.GenTextures(1, &t.arrayView);  // a view needs a name never bound
      gl_.TextureView(t.arrayView, GL_TEXTURE_2D_ARRAY, t.name,
                      glFormat(b.texture->format).internal, 0, 1, 0, 1);
      samplerState(t.arrayView, *b.texture);
      checkError("array view of " + b.texture->name);
    }
    return t.arrayView;
  }

  // One framebuffer object per distinct attachment set (textures and layers),
  // kept for reuse.
  GLuint framebuffer(const DriverPass& pass) {
    std::string key = ",";
    for (auto& a : pass.color)
      key += std::to_string(nameOf(a.texture.object)) + ",L" + std::to_string(a.layer) + ",";
    key += "d," + std::to_string(pass.depth.object ? nameOf(pass.depth.object) : 0) + ",";
    if (pass.color.empty() && !pass.depth.object)
      key += "size," + std::to_string(pass.width) + "x" + std::to_string(pass.height);
    auto it = fbos_.find(key);
    if (it != fbos_.end()) return it->second;
    GLuint fbo = 0;
    gl_.CreateFramebuffers(1, &fbo);
    std::vector<GLenum> drawBuffers;
    for (std::size_t i = 0; i < pass.color.size(); ++i) {
      const DriverColorTarget& a = pass.color[i];
      const GLenum at = GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i);
      if (a.texture.desc->layers > 1)
        gl_.NamedFramebufferTextureLayer(fbo, at, nameOf(a.texture.object), 0,
                                         static_cast<GLint>(a.layer));
      else
        gl_.NamedFramebufferTexture(fbo, at, nameOf(a.texture.object), 0);
      drawBuffers.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    }
    if (pass.depth.object)
      gl_.NamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, nameOf(pass.depth.object), 0);
    if (pass.color.empty() && !pass.depth.object) {
      gl_.NamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_WIDTH,
                                     static_cast<GLint>(pass.width));
      gl_.NamedFramebufferParameteri(fbo, GL_FRAMEBUFFER_DEFAULT_HEIGHT,
                                     static_cast<GLint>(pass.height));
    }
    if (drawBuffers.empty()) {
      const GLenum none = GL_NONE;
      gl_.NamedFramebufferDrawBuffers(fbo, 1, &none);
    } else {
      gl_.NamedFramebufferDrawBuffers(fbo, static_cast<GLsizei>(drawBuffers.size()),
                                      drawBuffers.data());
    }
    if (gl_.CheckNamedFramebufferStatus(fbo, GL_DRAW_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw DeviceError("incomplete framebuffer for pass '" + pass.name + "'");
    fbos_[key] = fbo;
    return fbo;
  }

  void applyState(const PipelineDesc& d) {
    if (d.depthTest || d.depthWrite) {
      // GL skips depth writes when the test is off; "always" keeps the write.
      gl_.Enable(GL_DEPTH_TEST);
      gl_.DepthFunc(d.depthTest ? glCompare(d.depthCompare) : GL_ALWAYS);
    } else {
      gl_.Disable(GL_DEPTH_TEST);
    }
    gl_.DepthMask(d.depthWrite ? GL_TRUE : GL_FALSE);
    if (d.logicOpOr) {
      gl_.Enable(GL_COLOR_LOGIC_OP);
      gl_.LogicOp(GL_OR);
    } else {
      gl_.Disable(GL_COLOR_LOGIC_OP);
    }
    for (std::size_t i = 0; i < d.colorFormats.size(); ++i) {
      const GLuint idx = static_cast<GLuint>(i);
      gl_.ColorMaski(idx, GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      const BlendState b = i < d.blend.size() ? d.blend[i] : BlendState::replace();
      if (b.enable && !isIntegerFormat(d.colorFormats[i])) {
        gl_.Enablei(GL_BLEND, idx);
        gl_.BlendFuncSeparatei(idx, glBlendFactor(b.srcColor), glBlendFactor(b.dstColor),
                               glBlendFactor(b.srcAlpha), glBlendFactor(b.dstAlpha));
        gl_.BlendEquationSeparatei(idx, glBlendOp(b.colorOp), glBlendOp(b.alphaOp));
      } else {
        gl_.Disablei(GL_BLEND, idx);
      }
    }
  }

  // The front end has checked kinds and declarations: bind each slot.
  void bind(const std::vector<DriverBinding>& bindings) {
    for (const auto& b : bindings) {
      switch (b.kind) {
        case BindingKind::UniformBuffer:
          gl_.BindBufferBase(GL_UNIFORM_BUFFER, b.binding, nameOf(b.object));
          break;
        case BindingKind::StorageBuffer:
          gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b.binding, nameOf(b.object));
          break;
        case BindingKind::SampledTexture:
          gl_.BindTextureUnit(b.binding, nameOf(b.object));
          break;
        case BindingKind::SampledTextureArray:
          gl_.BindTextureUnit(b.binding, arrayName(b));
          break;
        case BindingKind::AccelerationStructure:  // GL has no ray queries: never made
          break;
      }
    }
  }

  std::unique_ptr<GLPlatform> platform_;
  GLFunctions gl_;
  DeviceInfo info_;
  GLuint vao_ = 0;
  std::map<std::string, GLuint> fbos_;
  GLuint presentFbo_ = 0;                       // reads the texture present() shows
  GLint presentWidth_ = 0, presentHeight_ = 0;  // the window's size at the last present
  std::string passName_;
  struct Resolve {
    Resolve(GLuint f, std::size_t i, const DriverColorTarget& t, const DriverPass& p)
        : fbo(f), index(i), target(t), width(p.width), height(p.height) {}
    GLuint fbo;
    std::size_t index;  // colour attachment
    DriverColorTarget target;
    uint32_t width, height;
  };
  std::vector<Resolve> resolves_;  // of the open pass, blitted at its end
  uint32_t passSamples_ = 1;       // of the open pass
  Clock::time_point passStart_, frameStart_;
  bool gpuTiming_ = false;
  std::vector<GLuint> queries_;          // timestamp queries, two per pass, reused per frame
  std::vector<std::string> stampNames_;  // this frame's timed passes (GPU timing)
  std::vector<PassTiming> timings_;
  // Work counters (ARB_pipeline_statistics_query and an occlusion query), in
  // PassWork's order: the queries of each pass of a frame, and whether it was
  // a render pass (compute passes have no samples-passed query).
  static constexpr std::array<GLenum, 8> kCounterTargets{
      GL_VERTICES_SUBMITTED_ARB,         GL_PRIMITIVES_SUBMITTED_ARB,
      GL_VERTEX_SHADER_INVOCATIONS_ARB,  GL_CLIPPING_INPUT_PRIMITIVES_ARB,
      GL_CLIPPING_OUTPUT_PRIMITIVES_ARB, GL_FRAGMENT_SHADER_INVOCATIONS_ARB,
      GL_COMPUTE_SHADER_INVOCATIONS_ARB, GL_SAMPLES_PASSED};
  bool statistics_ = false;
  std::vector<std::array<GLuint, 8>> counterQueries_;
  std::vector<bool> counted_;
};

}  // namespace

std::unique_ptr<Driver> createGLDriver(const DeviceOptions& opts) {
  std::unique_ptr<GLPlatform> platform;
  if (opts.platform == "egl" || opts.platform.empty())
    platform = createEGLPlatform();
  else if (opts.platform == "osmesa")
    platform = createOSMesaPlatform();
  else if (opts.platform == "window")
    platform = createWindowGLPlatform(opts.windowWidth, opts.windowHeight, opts.windowTitle);
  else
    throw DeviceError("unknown GL platform '" + opts.platform + "' (valid: egl, osmesa, window)");
  return std::make_unique<GLDriver>(std::move(platform));
}

}  // namespace sb
