// The Device interface on OpenGL 4.5 core (direct state access).
#include "backends/gl/gl_device.h"

#include <chrono>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "backends/gl/gl_functions.h"
#include "backends/gl/gl_platform.h"
#include "backends/shader_source.h"

namespace sb {
namespace {

struct GLFormat {
  GLenum internal, format, type;
};

GLFormat glFormat(Format f) {
  switch (f) {
    case Format::RGBA8:
      return {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE};
    case Format::RGBA16F:
      return {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT};
    case Format::RGBA32F:
      return {GL_RGBA32F, GL_RGBA, GL_FLOAT};
    case Format::R32F:
      return {GL_R32F, GL_RED, GL_FLOAT};
    case Format::RG32F:
      return {GL_RG32F, GL_RG, GL_FLOAT};
    case Format::R32UI:
      return {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT};
    case Format::RGBA32UI:
      return {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT};
    case Format::Depth32F:
      return {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT};
  }
  return {0, 0, 0};
}

GLenum glCompare(CompareOp op) {
  switch (op) {
    case CompareOp::Never:
      return GL_NEVER;
    case CompareOp::Less:
      return GL_LESS;
    case CompareOp::LessEqual:
      return GL_LEQUAL;
    case CompareOp::Equal:
      return GL_EQUAL;
    case CompareOp::Greater:
      return GL_GREATER;
    case CompareOp::GreaterEqual:
      return GL_GEQUAL;
    case CompareOp::NotEqual:
      return GL_NOTEQUAL;
    case CompareOp::Always:
      return GL_ALWAYS;
  }
  return GL_LESS;
}

GLenum glBlendFactor(BlendFactor f) {
  switch (f) {
    case BlendFactor::Zero:
      return GL_ZERO;
    case BlendFactor::One:
      return GL_ONE;
    case BlendFactor::SrcColor:
      return GL_SRC_COLOR;
    case BlendFactor::OneMinusSrcColor:
      return GL_ONE_MINUS_SRC_COLOR;
    case BlendFactor::SrcAlpha:
      return GL_SRC_ALPHA;
    case BlendFactor::OneMinusSrcAlpha:
      return GL_ONE_MINUS_SRC_ALPHA;
    case BlendFactor::DstColor:
      return GL_DST_COLOR;
    case BlendFactor::OneMinusDstColor:
      return GL_ONE_MINUS_DST_COLOR;
    case BlendFactor::DstAlpha:
      return GL_DST_ALPHA;
    case BlendFactor::OneMinusDstAlpha:
      return GL_ONE_MINUS_DST_ALPHA;
  }
  return GL_ONE;
}

GLenum glBlendOp(BlendOp op) {
  switch (op) {
    case BlendOp::Add:
      return GL_FUNC_ADD;
    case BlendOp::Subtract:
      return GL_FUNC_SUBTRACT;
    case BlendOp::ReverseSubtract:
      return GL_FUNC_REVERSE_SUBTRACT;
    case BlendOp::Min:
      return GL_MIN;
    case BlendOp::Max:
      return GL_MAX;
  }
  return GL_FUNC_ADD;
}

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

class GLDevice : public Device {
 public:
  explicit GLDevice(std::unique_ptr<GLPlatform> platform) : platform_(std::move(platform)) {
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
    info_.timing = "cpu clock per pass (glFinish before and after)";
    info_.lines = "aliased (diamond exit)";
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

  ~GLDevice() override {
    for (auto& [key, fbo] : fbos_) gl_.DeleteFramebuffers(1, &fbo);
    for (auto& [id, b] : buffers_) gl_.DeleteBuffers(1, &b.name);
    for (auto& [id, t] : textures_) gl_.DeleteTextures(1, &t.name);
    for (auto& [id, p] : pipelines_) gl_.DeleteProgram(p.program);
    gl_.DeleteVertexArrays(1, &vao_);
  }

  DeviceInfo info() const override { return info_; }

  Buffer createBuffer(const BufferDesc& desc, const void* data) override {
    if (desc.bytes == 0) throw DeviceError("buffer '" + desc.name + "' has zero size");
    BufferRec r{desc, 0};
    gl_.CreateBuffers(1, &r.name);
    gl_.NamedBufferStorage(r.name, static_cast<GLsizeiptr>(desc.bytes), data,
                           GL_DYNAMIC_STORAGE_BIT);
    checkError("createBuffer " + desc.name);
    const uint32_t id = ++nextId_;
    buffers_[id] = r;
    return Buffer{id};
  }

  void updateBuffer(Buffer b, const void* data, std::size_t bytes, std::size_t offset) override {
    if (inPass_) throw DeviceError("updateBuffer inside a pass");
    auto& r = buffer(b);
    if (offset + bytes > r.desc.bytes)
      throw DeviceError("updateBuffer past the end of " + r.desc.name);
    gl_.NamedBufferSubData(r.name, static_cast<GLintptr>(offset), static_cast<GLsizeiptr>(bytes),
                           data);
  }

  void fillBuffer(Buffer b, uint32_t value) override {
    if (inPass_) throw DeviceError("fillBuffer inside a pass");
    gl_.ClearNamedBufferData(buffer(b).name, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &value);
  }

  Texture createTexture(const TextureDesc& desc) override {
    if (desc.width == 0 || desc.height == 0)
      throw DeviceError("texture '" + desc.name + "' has zero size");
    TextureRec r{desc, 0};
    const GLFormat f = glFormat(desc.format);
    gl_.CreateTextures(GL_TEXTURE_2D, 1, &r.name);
    gl_.TextureStorage2D(r.name, 1, f.internal, static_cast<GLsizei>(desc.width),
                         static_cast<GLsizei>(desc.height));
    const GLint filter =
        desc.linearFilter && !isIntegerFormat(desc.format) ? GL_LINEAR : GL_NEAREST;
    gl_.TextureParameteri(r.name, GL_TEXTURE_MIN_FILTER, filter);
    gl_.TextureParameteri(r.name, GL_TEXTURE_MAG_FILTER, filter);
    gl_.TextureParameteri(r.name, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl_.TextureParameteri(r.name, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    checkError("createTexture " + desc.name);
    const uint32_t id = ++nextId_;
    textures_[id] = r;
    return Texture{id};
  }

  Pipeline createPipeline(const PipelineDesc& desc) override {
    PipelineRec r{desc, gl_.CreateProgram()};
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
        gl_.DeleteProgram(r.program);
        throw DeviceError(describeCompileError(*code, desc.technique, log));
      }
      gl_.AttachShader(r.program, s);
      shaders.push_back(s);
    };
    addStage(desc.vertex, GL_VERTEX_SHADER);
    addStage(desc.fragment, GL_FRAGMENT_SHADER);
    addStage(desc.compute, GL_COMPUTE_SHADER);
    gl_.LinkProgram(r.program);
    for (GLuint s : shaders) gl_.DeleteShader(s);
    GLint ok = 0;
    gl_.GetProgramiv(r.program, GL_LINK_STATUS, &ok);
    if (!ok) {
      std::string log = shaderLog(r.program, true);
      gl_.DeleteProgram(r.program);
      throw DeviceError("shader link error in pipeline '" + desc.name + "' (technique '" +
                        desc.technique + "'):\n" + log);
    }
    // The ShaderCode pointers are not kept: only the fixed state is.
    r.desc.vertex = r.desc.fragment = r.desc.compute = nullptr;
    const uint32_t id = ++nextId_;
    pipelines_[id] = r;
    return Pipeline{id};
  }

  void destroy(Buffer b) override {
    auto it = buffers_.find(b.id);
    if (it == buffers_.end()) return;
    gl_.DeleteBuffers(1, &it->second.name);
    buffers_.erase(it);
  }

  void destroy(Texture t) override {
    auto it = textures_.find(t.id);
    if (it == textures_.end()) return;
    // Framebuffers that used it are dropped too.
    std::string needle = ",";
    needle += std::to_string(t.id);
    needle += ",";
    for (auto f = fbos_.begin(); f != fbos_.end();) {
      if (f->first.find(needle) != std::string::npos) {
        gl_.DeleteFramebuffers(1, &f->second);
        f = fbos_.erase(f);
      } else {
        ++f;
      }
    }
    gl_.DeleteTextures(1, &it->second.name);
    textures_.erase(it);
  }

  void beginFrame() override {
    if (inFrame_) throw DeviceError("beginFrame twice");
    inFrame_ = true;
    timings_.clear();
    gl_.Finish();  // earlier uploads do not count against the first pass
  }

  void beginPass(const PassDesc& pass) override {
    if (!inFrame_ || inPass_) throw DeviceError("beginPass outside a frame or inside a pass");
    inPass_ = true;
    passName_ = pass.name;
    passSampled_ = pass.sampledTextures;
    // Storage writes of earlier passes become visible (the Vulkan backend
    // puts a full barrier here too).
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    GLuint fbo = framebuffer(pass);
    gl_.BindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo);
    uint32_t w = pass.width, h = pass.height;
    for (auto& a : pass.color) {
      w = texture(a.texture).desc.width;
      h = texture(a.texture).desc.height;
    }
    if (pass.depth.texture) {
      w = texture(pass.depth.texture).desc.width;
      h = texture(pass.depth.texture).desc.height;
    }
    gl_.Viewport(0, 0, static_cast<GLsizei>(w), static_cast<GLsizei>(h));
    gl_.Finish();
    passStart_ = Clock::now();
    for (std::size_t i = 0; i < pass.color.size(); ++i) {
      const auto& a = pass.color[i];
      if (a.load != LoadOp::Clear) continue;
      gl_.ColorMaski(static_cast<GLuint>(i), GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
      if (isIntegerFormat(texture(a.texture).desc.format))
        gl_.ClearNamedFramebufferuiv(fbo, GL_COLOR, static_cast<GLint>(i), a.clearUint.data());
      else
        gl_.ClearNamedFramebufferfv(fbo, GL_COLOR, static_cast<GLint>(i), a.clear.data());
    }
    if (pass.depth.texture && pass.depth.load == LoadOp::Clear) {
      gl_.DepthMask(GL_TRUE);
      gl_.ClearNamedFramebufferfv(fbo, GL_DEPTH, 0, &pass.depth.clear);
    }
  }

  void draw(Pipeline p, const std::vector<Binding>& bindings, uint32_t vertexCount,
            uint32_t instanceCount) override {
    if (!inPass_) throw DeviceError("draw outside a pass");
    auto& r = pipeline(p);
    gl_.UseProgram(r.program);
    applyState(r.desc);
    bind(r.desc, bindings, true);
    gl_.DrawArraysInstanced(r.desc.topology == Topology::Lines ? GL_LINES : GL_TRIANGLES, 0,
                            static_cast<GLsizei>(vertexCount), static_cast<GLsizei>(instanceCount));
  }

  void endPass() override {
    if (!inPass_) throw DeviceError("endPass without beginPass");
    gl_.Finish();  // GL timer queries on llvmpipe miss vertex work: time with the CPU
    timings_.push_back(
        {passName_, std::chrono::duration<double, std::milli>(Clock::now() - passStart_).count()});
    inPass_ = false;
    checkError("pass " + passName_);
  }

  void dispatch(const std::string& passName, Pipeline p, const std::vector<Binding>& bindings,
                uint32_t x, uint32_t y, uint32_t z) override {
    if (!inFrame_ || inPass_) throw DeviceError("dispatch outside a frame or inside a pass");
    auto& r = pipeline(p);
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.Finish();
    const auto start = Clock::now();
    gl_.UseProgram(r.program);
    bind(r.desc, bindings, false);
    gl_.DispatchCompute(x, y, z);
    gl_.Finish();
    timings_.push_back(
        {passName, std::chrono::duration<double, std::milli>(Clock::now() - start).count()});
    checkError("dispatch " + passName);
  }

  void endFrame() override {
    if (!inFrame_ || inPass_) throw DeviceError("endFrame outside a frame or inside a pass");
    gl_.MemoryBarrier(GL_ALL_BARRIER_BITS);
    gl_.Finish();
    inFrame_ = false;
    checkError("endFrame");
  }

  std::vector<PassTiming> lastFrameTimings() const override { return timings_; }

  TextureDesc describe(Texture t) const override {
    auto it = textures_.find(t.id);
    if (it == textures_.end()) throw DeviceError("describe: unknown texture");
    return it->second.desc;
  }

  std::vector<uint8_t> readTexture(Texture t) override {
    auto& r = texture(t);
    const GLFormat f = glFormat(r.desc.format);
    std::vector<uint8_t> out(r.desc.width * r.desc.height * bytesPerPixel(r.desc.format));
    gl_.GetTextureImage(r.name, 0, f.format, f.type, static_cast<GLsizei>(out.size()), out.data());
    checkError("readTexture " + r.desc.name);
    return out;
  }

  std::vector<uint8_t> readBuffer(Buffer b) override {
    auto& r = buffer(b);
    std::vector<uint8_t> out(r.desc.bytes);
    gl_.GetNamedBufferSubData(r.name, 0, static_cast<GLsizeiptr>(out.size()), out.data());
    checkError("readBuffer " + r.desc.name);
    return out;
  }

  std::vector<ResourceBytes> allocations() const override {
    std::vector<ResourceBytes> out;
    for (auto& [id, b] : buffers_) out.push_back({b.desc.name, b.desc.owner, b.desc.bytes});
    for (auto& [id, t] : textures_)
      out.push_back(
          {t.desc.name, t.desc.owner, t.desc.width * t.desc.height * bytesPerPixel(t.desc.format)});
    return out;
  }

 private:
  struct BufferRec {
    BufferDesc desc;
    GLuint name;
  };
  struct TextureRec {
    TextureDesc desc;
    GLuint name;
  };
  struct PipelineRec {
    PipelineDesc desc;
    GLuint program;
  };

  BufferRec& buffer(Buffer b) {
    auto it = buffers_.find(b.id);
    if (it == buffers_.end()) throw DeviceError("unknown buffer handle");
    return it->second;
  }
  TextureRec& texture(Texture t) {
    auto it = textures_.find(t.id);
    if (it == textures_.end()) throw DeviceError("unknown texture handle");
    return it->second;
  }
  PipelineRec& pipeline(Pipeline p) {
    auto it = pipelines_.find(p.id);
    if (it == pipelines_.end()) throw DeviceError("unknown pipeline handle");
    return it->second;
  }

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

  void checkError(const std::string& what) {
    GLenum e = gl_.GetError();
    if (e != GL_NO_ERROR) throw DeviceError(std::string(glErrorName(e)) + " in " + what);
  }

  // One framebuffer object per distinct attachment set, kept for reuse.
  GLuint framebuffer(const PassDesc& pass) {
    if (pass.color.empty() && !pass.depth.texture && (pass.width == 0 || pass.height == 0))
      throw DeviceError("beginPass('" + pass.name + "'): no attachments and no size");
    std::string key = ",";
    for (auto& a : pass.color) key += std::to_string(a.texture.id) + ",";
    key += "d," + std::to_string(pass.depth.texture.id) + ",";
    if (pass.color.empty() && !pass.depth.texture)
      key += "size," + std::to_string(pass.width) + "x" + std::to_string(pass.height);
    auto it = fbos_.find(key);
    if (it != fbos_.end()) return it->second;
    GLuint fbo = 0;
    gl_.CreateFramebuffers(1, &fbo);
    std::vector<GLenum> drawBuffers;
    for (std::size_t i = 0; i < pass.color.size(); ++i) {
      gl_.NamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i),
                                  texture(pass.color[i].texture).name, 0);
      drawBuffers.push_back(GL_COLOR_ATTACHMENT0 + static_cast<GLenum>(i));
    }
    if (pass.depth.texture)
      gl_.NamedFramebufferTexture(fbo, GL_DEPTH_ATTACHMENT, texture(pass.depth.texture).name, 0);
    if (pass.color.empty() && !pass.depth.texture) {
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

  void bind(const PipelineDesc& d, const std::vector<Binding>& bindings, bool graphics) {
    for (const auto& b : bindings) {
      const BindingSlot* slot = nullptr;
      for (const auto& s : d.bindings)
        if (s.binding == b.binding) slot = &s;
      if (!slot)
        throw DeviceError("pipeline '" + d.name + "' has no binding " + std::to_string(b.binding));
      switch (slot->kind) {
        case BindingKind::UniformBuffer:
          gl_.BindBufferBase(GL_UNIFORM_BUFFER, b.binding, buffer(b.buffer).name);
          break;
        case BindingKind::StorageBuffer:
          gl_.BindBufferBase(GL_SHADER_STORAGE_BUFFER, b.binding, buffer(b.buffer).name);
          break;
        case BindingKind::SampledTexture: {
          bool declared = !graphics;
          for (auto& t : passSampled_) declared = declared || t.id == b.texture.id;
          if (!declared)
            throw DeviceError("pass '" + passName_ + "' samples texture '" +
                              texture(b.texture).desc.name + "' it did not declare");
          gl_.BindTextureUnit(b.binding, texture(b.texture).name);
          break;
        }
      }
    }
  }

  std::unique_ptr<GLPlatform> platform_;
  GLFunctions gl_;
  DeviceInfo info_;
  GLuint vao_ = 0;
  uint32_t nextId_ = 0;
  std::map<uint32_t, BufferRec> buffers_;
  std::map<uint32_t, TextureRec> textures_;
  std::map<uint32_t, PipelineRec> pipelines_;
  std::map<std::string, GLuint> fbos_;
  bool inFrame_ = false, inPass_ = false;
  std::string passName_;
  std::vector<Texture> passSampled_;
  Clock::time_point passStart_;
  std::vector<PassTiming> timings_;
};

}  // namespace

std::unique_ptr<Device> createGLDevice(const DeviceOptions& opts) {
  std::unique_ptr<GLPlatform> platform;
  if (opts.platform == "egl" || opts.platform.empty())
    platform = createEGLPlatform();
  else if (opts.platform == "osmesa")
    platform = createOSMesaPlatform();
  else
    throw DeviceError("unknown GL platform '" + opts.platform + "' (valid: egl, osmesa)");
  return std::make_unique<GLDevice>(std::move(platform));
}

}  // namespace sb
