#include "techniques/dom/dom.h"

#include <cmath>
#include <cstdlib>

#include "render/common/opacity_filter.h"
#include "render/common/shader_library.h"
#include "techniques/dom/layers.h"
#include "techniques/dom/slots.h"
#include "techniques/dom/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_DOM_PARAMS, kDepth = SB_SLOT_DOM_DEPTH,
                   kMaps = SB_SLOT_DOM_MAPS;

}  // namespace

void DeepOpacityMaps::finish(Options& opt) {
  if (opt.spacing != kSpacingList) return;
  opt.spacing = glsl::kDomLinear;  // the boundaries come from the list
  const std::string& text = opt.listText;
  std::size_t begin = 0;
  while (begin <= text.size()) {
    const std::size_t end = std::min(text.find(';', begin), text.size());
    const std::string item = text.substr(begin, end - begin);
    char* rest = nullptr;
    const float v = std::strtof(item.c_str(), &rest);
    if (item.empty() || *rest != '\0' || !(v > 0.0f) || !std::isfinite(v))
      throw InputError(
          "shadow technique 'dom': list= wants positive numbers separated by ';', "
          "got '" +
          text + "'");
    opt.list.push_back(v);
    begin = end + 1;
  }
  if (opt.list.size() != opt.layers)
    throw InputError("shadow technique 'dom': list= has " + std::to_string(opt.list.size()) +
                     " sizes for " + std::to_string(opt.layers) + " layers");
}

void DeepOpacityMaps::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);

  // The layer size s: absolute, or a fraction of the hair's depth range from
  // the light (from the hair points projected on the CPU).
  const DepthRange range = depthRange(hairLightDistances(dev, scene, view.viewProj));
  const float extent = range.farZ - range.nearZ;
  const float size = opt_.sizeAbs > 0.0f ? opt_.sizeAbs : opt_.sizeFrac * extent;
  const int K = static_cast<int>(opt_.layers);
  // extend: past the range plus one step of z0's quantization (z0 rounds down).
  const float quantum =
      opt_.depthBits < 32 ? 1.0f / (std::exp2(float(opt_.depthBits)) - 1.0f) : 0.0f;
  d_ = domBoundaries(K, opt_.spacing, size, opt_.list, opt_.beyond, extent + quantum);

  DomParams p{};
  p.domViewProj = view.viewProj;
  p.domParams = glm::vec4(opt_.bias, float(opt_.size), scene.shadowAlpha, float(opt_.depthBits));
  p.domLayout = glm::ivec4(K, int(targets()), opt_.beyond, opt_.filter);
  for (int k = 0; k <= K; ++k) p.domD[k / 4][k % 4] = d_[std::size_t(k)];
  params_ = dev.createBuffer({"dom.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);

  // z0: the depth buffer of a depth-only pass (the paper's depth map).
  depth_ = dev.createTexture(
      {"dom.depth", Owner::Shadow, Format::Depth32F, opt_.size, opt_.size, false});
  maps_ = dev.createTexture(
      {"dom.opacity", Owner::Shadow, Format::RGBA32F, opt_.size, opt_.size, false, targets()});
  if (!scene.hasHair()) return;

  const ShaderCode vert = Geometry::strandVertexShader(s);
  {
    const ShaderCode frag = loadShader("render/common/depth_only.frag");
    PipelineDesc d = depthPass().pipeline(dev, "dom.depth", "dom");
    d.vertex = &vert;
    d.topology = Geometry::strandTopology(s);
    d.fragment = &frag;
    d.depthCompare = CompareOp::Less;
    depthPipeline_ = dev.createPipeline(d);
  }
  ShaderDefines defs;
  defs.defines.push_back({"SB_DOM_TARGETS", std::to_string(targets())});
  defs.defines.push_back({"SB_DOM_COUNTING", opt_.thesisCounting ? "1" : "0"});
  const ShaderCode frag = loadShader("techniques/dom/opacity.frag", defs);
  PipelineDesc d = opacityPass().pipeline(dev, "dom.opacity", "dom");
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.fragment = &frag;
  d.blend.assign(targets(), BlendState::additive());
  opacityPipeline_ = dev.createPipeline(d);
}

// The paper's first step: the nearest hair depth z0 per texel, a depth-only
// pass with the depth test (no colour targets), z0 stored once. depth_bits
// quantizes z0 where it is read (quantizing is monotonic, so the quantized
// minimum is the minimum of the quantized depths, as the min blending of the
// colour pass this replaced stored it).
Pass DeepOpacityMaps::depthPass() const {
  return Pass("dom.depth")
      .depth(depth_, LoadOp::Clear)
      .inputs(Geometry::inputs(*scene_, lightView_));
}

// Each fragment adds its opacity to the layers behind it (z - z0 against d_k).
Pass DeepOpacityMaps::opacityPass() const {
  Pass p("dom.opacity");
  for (uint32_t t = 0; t < targets(); ++t) p.color(maps_, LoadOp::Clear, {0, 0, 0, 0}, t);
  return p.inputs(Geometry::inputs(*scene_, lightView_))
      .uniform(kParams, params_)
      .sample(kDepth, depth_);
}

void DeepOpacityMaps::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add(depthPass(),
            [this, &dev, vertices, p = depthPass()] { p.draw(dev, depthPipeline_, vertices); });
  graph.add(opacityPass(),
            [this, &dev, vertices, p = opacityPass()] { p.draw(dev, opacityPipeline_, vertices); });
}

ShadowLookup DeepOpacityMaps::lookup() const {
  ShadowLookup l{"techniques/dom/lookup.glsl"};
  l.inputs.uniform(kParams, params_).sampleArray(kMaps, maps_).sample(kDepth, depth_);
  opaque_.addTo(l);
  return l;
}

}  // namespace sb
