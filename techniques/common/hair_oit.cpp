#include "techniques/common/hair_oit.h"

#include "techniques/common/shader_library.h"
#include "techniques/kajiya_kay/shading.h"

namespace sb {

void HairOit::setupCommon(Device& dev, const GpuScene& scene, const RenderSettings& s,
                          const KajiyaKayShading& shading, const OitTargets& targets) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  targets_ = targets;
  composite_.setup(dev, s, shading.viewUbo(), targets, name());
  counts_ = dev.createBuffer(
      {name() + ".counts", "oit", BufferUsage::Storage, std::size_t(s.width) * s.height * 4});
  count_ = makeHairCountPipeline(dev, s, kCountsBinding, true, name());
}

PassDesc HairOit::hairPass(const std::string& name, bool first) const {
  PassDesc pass;
  pass.name = name;
  pass.depth = {targets_.depth, first && !targets_.opaqueDrawn ? LoadOp::Clear : LoadOp::Load,
                1.0f};
  pass.sampledTextures = shading_->sampledTextures();
  return pass;
}

Pipeline HairOit::hairPipeline(Device& dev, const std::string& name, const std::string& fragShader,
                               ShaderDefines defs, const std::vector<uint32_t>& storage) const {
  const ShaderDefines hair = shading_->hairDefines();
  for (auto& [alias, file] : hair.aliases) defs.aliases[alias] = file;
  defs.defines.insert(defs.defines.end(), hair.defines.begin(), hair.defines.end());
  const ShaderCode vert = Geometry::strandVertexShader(settings_);
  const ShaderCode frag = loadShader(fragShader, defs);
  PipelineDesc d;
  d.name = name;
  d.technique = this->name() + "+" + shading_->shadow().name();
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(settings_);
  d.hasDepth = d.depthTest = true;  // hair behind the opaque mesh is left out
  d.depthCompare = CompareOp::Less;
  d.bindings = shading_->hairSlots();
  for (uint32_t b : storage) d.bindings.push_back({b, BindingKind::StorageBuffer});
  return dev.createPipeline(d);
}

ListLayout HairOit::countFragments(Device& dev) {
  dev.fillBuffer(counts_, 0);
  dev.beginFrame();
  dev.beginPass(hairPass(name() + ".count", true));
  auto b = Geometry::bindings(*scene_, shading_->viewUbo());
  b.push_back(Binding::buf(kCountsBinding, counts_));
  dev.draw(count_, b, hairVertices());
  dev.endPass();
  dev.endFrame();
  ListLayout layout = layoutFromCounts(dev.readBuffer(counts_));
  complexity_ = layout.complexity;
  return layout;
}

std::vector<std::string> HairOit::graphReads() const {
  auto reads = shading_->shadowReads();
  if (targets_.opaqueDrawn) {  // otherwise the first pass clears the depth itself
    reads.push_back("depth");
    reads.push_back("color");
  }
  return reads;
}

}  // namespace sb
