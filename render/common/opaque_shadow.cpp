#include "render/common/opaque_shadow.h"

namespace sb {

void OpaqueShadow::setup(Device& dev, const GpuScene& scene, uint32_t size, Buffer lightViewUbo,
                         const std::string& technique) {
  scene_ = &scene;
  technique_ = technique;
  lightView_ = lightViewUbo;
  if (!scene.hasMesh()) return;
  depth_ = dev.createTexture(
      {technique + ".opaque_depth", Owner::Shadow, Format::Depth32F, size, size, false});
  const ShaderCode vert = Geometry::meshVertexShader();
  const ShaderCode frag = loadShader("render/common/depth_only.frag");
  PipelineDesc d = pass().pipeline(dev, technique + ".opaque", technique);
  d.vertex = &vert;
  d.fragment = &frag;
  pipeline_ = dev.createPipeline(d);
}

ViewUniforms LightMapShadow::setupLight(Device& dev, const GpuScene& scene, const RenderSettings& s,
                                        uint32_t size) {
  scene_ = &scene;
  settings_ = s;
  const ViewUniforms view = lightView(s, size, size);
  lightView_ = createLightViewBuffer(dev, view, name());
  opaque_.setup(dev, scene, size, lightView_, name());
  return view;
}

Pass OpaqueShadow::pass() const {
  return Pass(technique_ + ".opaque")
      .depth(depth_, LoadOp::Clear)
      .inputs(Geometry::inputs(*scene_, lightView_));
}

void OpaqueShadow::addPass(FrameGraph& graph, Device& dev) {
  if (!active()) return;
  graph.add(pass(),
            [this, &dev, p = pass()] { p.draw(dev, pipeline_, scene_->meshTriangles * 3); });
}

void OpaqueShadow::addTo(ShadowLookup& lookup) const {
  lookup.defines.defines.push_back({"SB_OPAQUE_SHADOW", active() ? "1" : "0"});
  if (active()) lookup.inputs.sample(kBinding, depth_);
}

}  // namespace sb
