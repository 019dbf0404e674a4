#include "render/outputs/visibility/visibility.h"

#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"

namespace sb {

void VisibilityOutput::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                             const HairShading& shading) {
  scene_ = &scene;
  shading_ = &shading;
  settings_ = s;
  image_ =
      dev.createTexture({"visibility.image", Owner::Frame, Format::R32F, s.width, s.height, false});
  depth_ = dev.createTexture(
      {"visibility.depth", Owner::Frame, Format::Depth32F, s.width, s.height, false});
  const ShaderCode frag =
      loadShader("render/outputs/visibility/visibility.frag", shading.hairDefines());
  PipelineDesc d = pass().pipeline(dev, "visibility", "visibility+" + shading.shadow().name());
  d.fragment = &frag;
  d.depthCompare = CompareOp::Less;
  const auto pipelines = Geometry::pipelines(dev, d, scene, s, "visibility");
  hair_ = pipelines.hair;
  mesh_ = pipelines.mesh;
}

Pass VisibilityOutput::pass() const {
  return Pass("visibility")
      .color(image_, LoadOp::Clear, {-1.0f, 0, 0, 0})
      .depth(depth_, LoadOp::Clear)
      .inputs(shading_->hairInputs());
}

void VisibilityOutput::addPasses(FrameGraph& graph, Device& dev) {
  graph.add(pass(), [this, &dev, p = pass()] {
    p.draw(dev, {{mesh_, scene_->meshTriangles * 3},
                 {hair_, Geometry::strandVertexCount(*scene_, settings_)}});
  });
}

}  // namespace sb
