#include "backends/vulkan/vk_shader.h"

#include <glslang/Public/ResourceLimits.h>
#include <glslang/Public/ShaderLang.h>
#include <glslang/SPIRV/GlslangToSpv.h>

#include <map>
#include <mutex>
#include <utility>

namespace sb {

namespace {

std::once_flag g_glslangInit;
std::mutex g_cacheMutex;
std::map<std::pair<int, std::string>, std::vector<uint32_t>> g_spirvCache;

EShLanguage toLanguage(ShaderStage stage) {
  switch (stage) {
    case ShaderStage::Vertex:
      return EShLangVertex;
    case ShaderStage::Fragment:
      return EShLangFragment;
    case ShaderStage::Compute:
      return EShLangCompute;
    case ShaderStage::Mesh:
      return EShLangMesh;
  }
  return EShLangVertex;
}

}  // namespace

std::vector<uint32_t> compileVulkanSpirv(const ShaderCode& code, ShaderStage stage,
                                         const std::string& technique, bool uniformsAsStorage) {
  std::call_once(g_glslangInit, [] { glslang::InitializeProcess(); });
  std::string source = completeShaderSource(code, ShaderApi::Vulkan);
  // After the #version line, which must come first; before "#line 1 0", so
  // line numbers in errors are unchanged.
  if (uniformsAsStorage) source.insert(source.find('\n') + 1, "#define SB_UNIFORMS_AS_STORAGE 1\n");
  const auto key = std::make_pair(static_cast<int>(stage), source);
  {
    std::lock_guard<std::mutex> lock(g_cacheMutex);
    auto it = g_spirvCache.find(key);
    if (it != g_spirvCache.end()) return it->second;
  }

  const EShLanguage lang = toLanguage(stage);
  const auto messages = static_cast<EShMessages>(EShMsgSpvRules | EShMsgVulkanRules);
  glslang::TShader shader(lang);
  const char* strings[] = {source.c_str()};
  // No string names: "#line N F" then reports F, which describeCompileError maps
  // to code.fileNames[F].
  shader.setStrings(strings, 1);
  shader.setEnvInput(glslang::EShSourceGlsl, lang, glslang::EShClientVulkan, 100);
  shader.setEnvClient(glslang::EShClientVulkan, glslang::EShTargetVulkan_1_3);
  shader.setEnvTarget(glslang::EShTargetSpv, glslang::EShTargetSpv_1_6);
  if (!shader.parse(GetDefaultResources(), 450, ECoreProfile, false, false, messages)) {
    throw DeviceError(describeCompileError(code, technique, shader.getInfoLog()));
  }
  glslang::TProgram program;
  program.addShader(&shader);
  if (!program.link(messages)) {
    throw DeviceError(describeCompileError(code, technique, program.getInfoLog()));
  }
  std::vector<uint32_t> spirv;
  spv::SpvBuildLogger logger;
  glslang::SpvOptions options;
  options.generateDebugInfo = false;
  options.disableOptimizer = false;
  options.validate = false;
  glslang::GlslangToSpv(*program.getIntermediate(lang), spirv, &logger, &options);
  const std::string log = logger.getAllMessages();
  if (spirv.empty()) {
    throw DeviceError(describeCompileError(code, technique, "SPIR-V generation failed\n" + log));
  }
  std::lock_guard<std::mutex> lock(g_cacheMutex);
  g_spirvCache.emplace(key, spirv);
  return spirv;
}

std::set<uint32_t> storageBufferBindings(const std::vector<uint32_t>& spirv) {
  constexpr uint32_t kOpDecorate = 71, kOpVariable = 59, kBinding = 33, kStorageBuffer = 12;
  std::map<uint32_t, uint32_t> bindingOf;  // id -> binding
  std::set<uint32_t> storageIds;
  // Instructions follow the 5-word header; each starts with (word count << 16) | opcode.
  for (std::size_t i = 5; i < spirv.size();) {
    const uint32_t words = spirv[i] >> 16, op = spirv[i] & 0xffffu;
    if (words == 0 || i + words > spirv.size()) break;
    if (op == kOpDecorate && words >= 4 && spirv[i + 2] == kBinding) {
      bindingOf[spirv[i + 1]] = spirv[i + 3];
    } else if (op == kOpVariable && words >= 4 && spirv[i + 3] == kStorageBuffer) {
      storageIds.insert(spirv[i + 2]);
    }
    i += words;
  }
  std::set<uint32_t> out;
  for (uint32_t id : storageIds) {
    if (auto it = bindingOf.find(id); it != bindingOf.end()) out.insert(it->second);
  }
  return out;
}

}  // namespace sb
