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

}  // namespace sb
