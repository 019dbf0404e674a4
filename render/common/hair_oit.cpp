#include "render/common/hair_oit.h"

#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"

namespace sb {

PipelineDesc transparentHairDesc(const Device& dev, const Pass& pass, const std::string& name,
                                 const std::string& technique, const ShaderCode& vert,
                                 const RenderSettings& s) {
  PipelineDesc d = pass.pipeline(dev, name, technique);
  d.vertex = &vert;
  d.topology = Geometry::strandTopology(s);
  d.depthWrite = false;  // also where the pass clears the depth (nothing opaque drawn)
  d.depthCompare = CompareOp::Less;
  return d;
}

void KeptInputsOit::keep(const GpuScene& scene, const RenderSettings& s, const HairShading& shading,
                         const OitTargets& targets) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  targets_ = targets;
}

void CompositedOit::keepInputs(Device& dev, const GpuScene& scene, const RenderSettings& s,
                               const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);
  composite_.setup(dev, s, shading.viewUbo(), targets, name());
}

void HairOit::setupCommon(Device& dev, const GpuScene& scene, const RenderSettings& s,
                          const HairShading& shading, const OitTargets& targets) {
  keepInputs(dev, scene, s, shading, targets);
  counts_ = dev.createBuffer(
      {name() + ".counts", Owner::Oit, BufferUsage::Storage, std::size_t(s.width) * s.height * 4});
  count_ = makeHairCountPipeline(dev, s, countPass(), kCountsBinding, name());
}

Pass HairOit::hairPass(const std::string& name, bool first) const {
  Pass p(name);
  if (first && !targets_.opaqueDrawn)
    p.depth(targets_.depth, LoadOp::Clear);
  else
    p.depthReadOnly(targets_.depth);
  return p.inputs(shading_->hairInputs());
}

Pipeline HairOit::hairPipeline(Device& dev, const Pass& pass, const std::string& fragShader,
                               ShaderDefines defs) const {
  defs.add(shading_->hairDefines());
  const ShaderCode vert = Geometry::strandVertexShader(settings_);
  const ShaderCode frag = loadShader(fragShader, defs);
  PipelineDesc d = transparentHairDesc(
      dev, pass, pass.name(), this->name() + "+" + shading_->shadow().name(), vert, settings_);
  d.fragment = &frag;
  return dev.createPipeline(d);
}

// Geometry only: the count needs no shading.
Pass HairOit::countPass() const {
  Pass p(name() + ".count");
  if (targets_.opaqueDrawn)
    p.depthReadOnly(targets_.depth);
  else
    p.depth(targets_.depth, LoadOp::Clear);
  return p.inputs(Geometry::inputs(*scene_, shading_->viewUbo())).storage(kCountsBinding, counts_);
}

ListLayout HairOit::countFragments(Device& dev) {
  dev.fillBuffer(counts_, 0);
  dev.beginFrame();
  countPass().draw(dev, count_, hairVertices());
  dev.endFrame();
  ListLayout layout = layoutFromCounts(dev.readBuffer(counts_));
  complexity_ = layout.complexity;
  return layout;
}

}  // namespace sb
