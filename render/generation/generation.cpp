#include "render/generation/generation.h"

#include "render/common/shader_library.h"
#include "render/generation/slots.h"
#include "render/generation/uniforms.h"
#include "render/graph/pass.h"

namespace sb {

namespace {
Pass generationPass(Buffer params, Buffer guidePoints, Buffer guideColors, Buffer neighbours,
                    Buffer placements, Buffer seeds, Buffer lods, Buffer guideOrder, Buffer points,
                    Buffer colors, Buffer segments) {
  Pass p("scene.generate");
  p.uniform(SB_SLOT_GEN_PARAMS, params)
      .readStorage(SB_SLOT_GEN_GUIDE_POINTS, guidePoints)
      .readStorage(SB_SLOT_GEN_GUIDE_COLORS, guideColors)
      .readStorage(SB_SLOT_GEN_NEIGHBOURS, neighbours)
      .readStorage(SB_SLOT_GEN_PLACEMENTS, placements)
      .readStorage(SB_SLOT_GEN_SEEDS, seeds)
      .readStorage(SB_SLOT_GEN_LODS, lods)
      .readStorage(SB_SLOT_GEN_GUIDE_ORDER, guideOrder)
      .storage(SB_SLOT_POINTS, points)
      .storage(SB_SLOT_COLORS, colors)
      .storage(SB_SLOT_SEGMENTS, segments);
  return p;
}

Buffer input(Device& dev, const std::string& name, const void* data, std::size_t bytes) {
  return dev.createBuffer({"scene." + name, Owner::Scene, BufferUsage::Storage, bytes}, data);
}
}  // namespace

std::string geometryRefusal(const std::string& geometry, const Scene& scene) {
  if (geometry == "mesh" && scene.groom.empty())
    return "mesh makes the strands from the scene's groom: give the scene guides=N (every "
           "n-th strand a guide) or instances=N (docs/geometry.md)";
  if (geometry == "compute" && scene.groom.empty())
    return "compute makes the strands from the scene's groom: give the scene guides=N (every "
           "n-th strand a guide) or instances=N (docs/geometry.md)";
  return "";
}

void StrandGeneration::setup(Device& dev, const Scene& scene, GpuScene& gpu) {
  const Groom& g = scene.groom;
  if (const std::string why = geometryRefusal("compute", scene); !why.empty())
    throw InputError("--geometry compute: " + why);
  const uint64_t total = g.totalPoints();
  total_ = static_cast<uint32_t>(total);
  GenerationParams params{};
  params.genSizes = {g.guideCount, g.points, g.strands, g.instanceCount()};
  params.genRule = {g.spread, g.offset, g.noise, g.clump};
  params.genMore = {g.alongStep, scene.hairAlpha, 0.0f, 0.0f};
  params.genTotal = {total_, 0u, 0u, 0u};
  params_ = dev.createBuffer(
      {"scene.generation_params", Owner::Scene, BufferUsage::Uniform, sizeof params}, &params);
  guidePoints_ =
      input(dev, "guide_points", g.guidePoints.data(), g.guidePoints.size() * sizeof(glm::vec4));
  guideColors_ =
      input(dev, "guide_colors", g.guideColors.data(), g.guideColors.size() * sizeof(glm::vec4));
  neighbours_ =
      input(dev, "guide_neighbours", g.neighbours.data(), g.neighbours.size() * sizeof(uint32_t));
  placements_ = input(dev, "instance_placements", g.placements.data(),
                      g.placements.size() * sizeof(glm::vec4));
  seeds_ = input(dev, "instance_seeds", g.instanceSeeds.data(),
                 g.instanceSeeds.size() * sizeof(uint32_t));
  static_assert(sizeof(GroomInstanceLod) == 16, "read as a uvec4");
  lods_ = input(dev, "instance_lods", g.lods.data(), g.lods.size() * sizeof(GroomInstanceLod));
  guideOrder_ =
      input(dev, "guide_order", g.guideOrder.data(), g.guideOrder.size() * sizeof(uint32_t));
  const uint64_t segments = g.totalStrands() * (g.points - 1);
  points_ = dev.createBuffer({"scene.points", Owner::Scene, BufferUsage::Storage, total * 16});
  colors_ = dev.createBuffer({"scene.colors", Owner::Scene, BufferUsage::Storage, total * 16});
  segments_ =
      dev.createBuffer({"scene.segments", Owner::Scene, BufferUsage::Storage, segments * 4});
  gpu.points = points_;
  gpu.colors = colors_;
  gpu.segments = segments_;
  gpu.segmentCount = static_cast<uint32_t>(segments);
  const Pass pass = generationPass(params_, guidePoints_, guideColors_, neighbours_, placements_,
                                   seeds_, lods_, guideOrder_, points_, colors_, segments_);
  const ShaderCode code = loadShader("render/generation/generate.comp");
  PipelineDesc d = pass.pipeline(dev, "scene.generate", "generation");
  d.compute = &code;
  pipeline_ = dev.createPipeline(d);
}

void StrandGeneration::run(Device& dev) {
  const Pass pass = generationPass(params_, guidePoints_, guideColors_, neighbours_, placements_,
                                   seeds_, lods_, guideOrder_, points_, colors_, segments_);
  const glm::uvec2 groups = dispatchGroups(total_);
  dev.beginFrame();
  pass.dispatch(dev, pipeline_, groups.x, groups.y);
  dev.endFrame();
}

}  // namespace sb
