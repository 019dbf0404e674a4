#include "backends/shader_source.h"

#include <regex>
#include <sstream>

namespace sb {

namespace {
// Lines the preamble adds before "#line 1 0"; #line resets numbering anyway.
const char* kGlPreamble =
    "#version 450 core\n"
    "#define SB_GL 1\n"
    "#define gl_VertexIndex gl_VertexID\n"
    "#define gl_InstanceIndex gl_InstanceID\n";
const char* kVulkanPreamble =
    "#version 450 core\n"
    "#define SB_VULKAN 1\n";
}  // namespace

std::string completeShaderSource(const ShaderCode& code, ShaderApi api) {
  std::string out = api == ShaderApi::GL ? kGlPreamble : kVulkanPreamble;
  // GL_EXT_ray_query needs GLSL 4.60 (glslang declares rayQueryEXT from 460
  // on); other shaders stay at 4.50, their SPIR-V unchanged.
  if (api == ShaderApi::Vulkan && code.text.find("GL_EXT_ray_query") != std::string::npos)
    out.replace(out.find("450"), 3, "460");
  out += "#line 1 0\n";
  out += code.text;
  return out;
}

std::string describeCompileError(const ShaderCode& code, const std::string& technique,
                                 const std::string& log) {
  // GL (Mesa) writes "0:12(3): error:"; glslang writes "ERROR: 0:12: ...".
  static const std::regex loc(R"((\d+):(\d+)(\(\d+\))?:)");
  std::string mapped;
  std::string rest = log;
  std::smatch m;
  while (std::regex_search(rest, m, loc)) {
    mapped += m.prefix();
    std::size_t idx = std::stoul(m[1].str());
    std::string file = idx < code.fileNames.size() ? code.fileNames[idx] : code.name;
    mapped += file + ":" + m[2].str() + ":";
    rest = m.suffix();
  }
  mapped += rest;
  std::ostringstream s;
  s << "shader compile error in " << code.name << " (technique '" << technique << "'):\n" << mapped;
  return s.str();
}

}  // namespace sb
