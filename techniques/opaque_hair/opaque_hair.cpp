#include "techniques/opaque_hair/opaque_hair.h"

#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"

namespace sb {

void OpaqueHair::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                       const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("render/shading/hair.frag", shading.hairDefines());
  PipelineDesc d = pass().pipeline(dev, "shading.hair", "kajiya_kay+" + shading.shadow().name());
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  d.depthCompare = CompareOp::Less;
  pipeline_ = dev.createPipeline(d);
}

// Over the opaque result when one was drawn, else clearing the targets.
Pass OpaqueHair::pass() const {
  Pass p("shading.hair");
  p.colorOver(targets_.color, targets_.opaqueDrawn, settings_.background);
  if (targets_.resolved) p.resolveInto(targets_.resolved);  // --msaa: the samples averaged
  return p.depth(targets_.depth, targets_.opaqueDrawn ? LoadOp::Load : LoadOp::Clear)
      .inputs(shading_->hairInputs());
}

void OpaqueHair::addPasses(FrameGraph& graph, Device& dev) {
  graph.add(pass(), [this, &dev, p = pass()] {
    p.draw(dev, pipeline_, Geometry::strandVertexCount(*scene_, settings_));
  });
}

}  // namespace sb
