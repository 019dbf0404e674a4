#include "techniques/rt_oit/rt_oit.h"

#include "base/errors.h"
#include "base/options.h"
#include "render/common/readback.h"
#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"
#include "techniques/rt_oit/slots.h"
#include "techniques/rt_oit/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_RT_OIT_PARAMS, kNodes = SB_SLOT_RT_OIT_NODES,
                   kSegments = SB_SLOT_RT_OIT_SEGMENTS, kStatus = SB_SLOT_RT_OIT_STATUS,
                   kOpaque = SB_SLOT_RT_OIT_OPAQUE, kScene = SB_SLOT_RT_OIT_SCENE;
constexpr uint32_t kTile = 8;  // trace.comp's workgroup side

}  // namespace

void RayTracedOit::check(Options& r) {
  if (r.k > 0 && r.maxHits > 0)
    throw InputError(
        "transparency technique 'rt': max_hits caps the walks of k=0 (every hit); "
        "with k=" +
        std::to_string(r.k) + " every hit is kept or merged: give one");
}

void RayTracedOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                         const HairShading& shading, const OitTargets& targets) {
  const rt::TierChoice tier =
      rt::chooseTier(o_.walk.tier, dev.info(), "transparency technique 'rt'");
  rayQuery_ = tier.rayQuery;
  tierReason_ = tier.reason;
  if (scene.segmentCount > kMaxSegments)
    throw InputError("transparency technique 'rt': " + std::to_string(scene.segmentCount) +
                     " segments; at most " + std::to_string(kMaxSegments) +
                     " (2^24: a segment's index is a float in the shader)");
  keepInputs(dev, scene, s, shading, targets);
  const glm::mat4 vp = cameraView(s).viewProj;
  // Its segments are capsules of one width in pixels (texels); world widths with coverage
  // would need a per-segment radius and alpha it does not have yet.
  if (s.primitive == Primitive::World)
    throw InputError(
        "transparency technique 'rt': --primitive world is not supported (lines or ribbons)");
  const float pixels = s.primitive == Primitive::Ribbons ? s.ribbonWidth : 1.0f;

  // One pixel is 2 |w| / (width * xScale) world units at clip w.
  const float xScale = glm::length(glm::vec3(vp[0][0], vp[1][0], vp[2][0]));
  const std::vector<rt::Segment> segs =
      rt::sceneSegments(dev, scene, vp, 2.0f / (float(s.width) * xScale), pixels);
  rt::Walk walk = rt::buildWalk(segs, rayQuery_, o_.walk.sah);
  // b.w: the segment's index, for its colours and the hits' order, as a float's
  // value (exact below 2^24, which setup checks); for ray queries slot i is
  // segment i, the index of its box.
  for (std::size_t k = 0; k < walk.bvh.order.size(); ++k)
    walk.packed[2 * k + 1].w = float(walk.bvh.order[k]);
  buildMs_ = walk.buildMs;
  nodeCount_ = uint32_t(walk.bvh.nodes.size());
  depth_ = walk.bvh.depth;
  segmentCount_ = uint32_t(segs.size());

  RtOitParams p{};
  p.rtoInvViewProj = glm::mat4(glm::inverse(glm::dmat4(vp)));
  p.rtoSize = glm::uvec4(s.width, s.height, o_.k, o_.maxHits);
  params_ = dev.createBuffer({"rt.oit_params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  walk_ = rt::uploadWalk(dev, walk, rayQuery_, "rt.oit_", Owner::Oit);
  status_ = dev.createBuffer({"rt.oit_status", Owner::Oit, BufferUsage::Storage, 16});

  ShaderDefines defs = shading.hairDefines();
  if (targets.opaqueDrawn) defs.defines.push_back({"SB_RT_OIT_OPAQUE", "1"});
  if (o_.k > 0) defs.defines.push_back({"SB_RT_OIT_K", std::to_string(o_.k)});
  if (rayQuery_) defs.defines.push_back({"SB_RT_OIT_RAY_QUERY", "1"});
  const ShaderCode comp = loadShader("techniques/rt_oit/trace.comp", defs);
  PipelineDesc d =
      tracePass().pipeline(dev, name() + ".trace", name() + "+" + shading.shadow().name());
  d.compute = &comp;
  trace_ = dev.createPipeline(d);
}

Pass RayTracedOit::tracePass() const {
  Pass p(name() + ".trace");
  Inputs walk;
  if (rayQuery_)
    walk.accelerationStructure(kScene, walk_.scene);
  else
    walk.readStorage(kNodes, walk_.nodes);
  p.inputs(shading_->hairInputs())
      .inputs(walk)
      .uniform(kParams, params_)
      .readStorage(kSegments, walk_.segments)
      .storage(kStatus, status_)
      .storage(AccumComposite::kAccumBinding, composite_.accum());
  if (targets_.opaqueDrawn) p.sample(kOpaque, targets_.depth);
  return p;
}

void RayTracedOit::addPasses(FrameGraph& graph, Device& dev) {
  graph.add(name(), {tracePass(), composite_.pass()}, [this, &dev] {
    dev.fillBuffer(status_, 0);
    tracePass().dispatch(dev, trace_, (settings_.width + kTile - 1) / kTile,
                         (settings_.height + kTile - 1) / kTile);
    composite_.record(dev);
  });
}

std::vector<Counter> RayTracedOit::counters(Device& dev) {
  const auto status = readBufferAs<uint32_t>(dev, status_);
  auto word = [&status](std::size_t i) { return i < status.size() ? double(status[i]) : 0.0; };
  return {{"rt.oit_bvh_build_ms", buildMs_},
          {"rt.oit_bvh_nodes", double(nodeCount_)},
          {"rt.oit_bvh_depth", double(depth_)},
          {"rt.oit_segments", double(segmentCount_)},
          {"rt.oit_hits", word(0)},
          {"rt.oit_pixels_capped", word(1)},
          {"rt.oit_pixels_merged", word(2)},
          {"rt.oit_tier_ray_query", rayQuery_ ? 1.0 : 0.0}};
}

std::vector<std::string> RayTracedOit::warnings(Device& dev) {
  const auto status = readBufferAs<uint32_t>(dev, status_);
  if (status.size() < 2 || status[1] == 0) return {};
  return {"rt: " + std::to_string(status[1]) + " pixels reached max_hits=" +
          std::to_string(o_.maxHits) + " (their farther hits are left out)"};
}

}  // namespace sb
