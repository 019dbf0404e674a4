#include "techniques/voxel/voxel.h"

#include <cstring>

#include "render/common/opacity.h"
#include "render/common/shader_library.h"
#include "techniques/voxel/slots.h"
#include "techniques/voxel/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_VOXEL_PARAMS, kGrid = SB_SLOT_VOXEL_GRID;

}  // namespace

void VoxelDensityShadow::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);
  // The volume's depth: the hair's range from the light (from the hair
  // points, exact for lines and ribbons), a little wider so that the farthest
  // fragment falls inside the last slice.
  const DepthRange r = paddedHairDepthRange(dev, scene, view.viewProj);
  VoxelParams p{};
  p.voxelViewProj = view.viewProj;
  p.voxelParams = glm::vec4(opt_.bias, float(opt_.size), scene.shadowAlpha, opt_.densityScale);
  p.voxelRange = glm::vec4(r.nearZ, r.farZ, float(opt_.steps), 0.0f);
  p.voxelCells = glm::vec4(float(columns()), float(opt_.grid), 0.0f, 0.0f);
  params_ = dev.createBuffer({"voxel.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  const std::size_t voxels = std::size_t(columns()) * columns() * opt_.grid;
  grid_ = dev.createBuffer({"voxel.grid", Owner::Shadow, BufferUsage::Storage, voxels * 4});
  if (!scene.hasHair()) return;
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("techniques/voxel/splat.frag");
  PipelineDesc d = splatPass().pipeline(dev, "voxel.splat", "voxel");
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  pipeline_ = dev.createPipeline(d);
}

// A hair pass from the light at the splat size (no attachments) into the grid.
Pass VoxelDensityShadow::splatPass() const {
  return Pass("voxel.splat")
      .size(opt_.size, opt_.size)
      .inputs(Geometry::inputs(*scene_, lightView_))
      .uniform(kParams, params_)
      .storage(kGrid, grid_);
}

void VoxelDensityShadow::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
  graph.add(splatPass(), [this, &dev, vertices, p = splatPass()] {
    dev.fillBuffer(grid_, 0);
    p.draw(dev, pipeline_, vertices);
  });
}

ShadowLookup VoxelDensityShadow::lookup() const {
  ShadowLookup l{"techniques/voxel/lookup.glsl"};
  l.inputs.uniform(kParams, params_).readStorage(kGrid, grid_);
  opaque_.addTo(l);
  return l;
}

// Voxels with hair and the fragments splatted (the grid's total).
std::vector<Counter> VoxelDensityShadow::counters(Device& dev) {
  const std::vector<uint8_t> bytes = dev.readBuffer(grid_);
  uint64_t occupied = 0, fragments = 0;
  for (std::size_t i = 0; i + 4 <= bytes.size(); i += 4) {
    uint32_t c = 0;
    std::memcpy(&c, bytes.data() + i, 4);
    occupied += c != 0;
    fragments += c;
  }
  return {{"voxel_occupied", double(occupied)},
          {"voxel_fragments", double(fragments)},
          {"voxel_grid_bytes", double(bytes.size())}};
}

}  // namespace sb
