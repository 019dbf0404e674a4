#include "techniques/rt/rt.h"

#include "base/errors.h"
#include "render/common/readback.h"
#include "techniques/rt/slots.h"
#include "techniques/rt/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_RT_PARAMS, kNodes = SB_SLOT_RT_NODES,
                   kSegments = SB_SLOT_RT_SEGMENTS, kStatus = SB_SLOT_RT_STATUS,
                   kScene = SB_SLOT_RT_SCENE;

}  // namespace

void RayTracedShadow::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const rt::TierChoice tier = rt::chooseTier(opt_.walk.tier, dev.info(), "shadow technique 'rt'");
  rayQuery_ = tier.rayQuery;
  tierReason_ = tier.reason;
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);
  const glm::mat4 proj = s.light.projection(), lightV = s.light.view();
  // One texel is 2 / size of the NDC square: 2 w / (size P00) world units at clip w.
  const float perW = 2.0f / (float(opt_.size) * proj[0][0]);
  // Its segments are capsules of one width in pixels (texels); world widths with coverage
  // would need a per-segment radius and alpha it does not have yet.
  if (s.primitive == Primitive::World)
    throw InputError(
        "shadow technique 'rt': --primitive world is not supported (lines or ribbons)");
  const float texels = s.primitive == Primitive::Ribbons ? s.ribbonWidth : 1.0f;

  const std::vector<rt::Segment> segs = rt::sceneSegments(dev, scene, view.viewProj, perW, texels);
  const rt::Walk walk = rt::buildWalk(segs, rayQuery_, opt_.walk.sah);
  buildMs_ = walk.buildMs;
  nodeCount_ = uint32_t(walk.bvh.nodes.size());
  depth_ = walk.bvh.depth;
  segmentCount_ = uint32_t(segs.size());

  RtParams p{};
  p.rtViewProj = view.viewProj;
  p.rtParams = glm::vec4(opt_.bias, float(opt_.size), scene.shadowAlpha, float(opt_.rays));
  const bool point = s.light.type == LightType::Point;
  p.rtLight = point ? glm::vec4(s.light.position, 1.0f)
                    : glm::vec4(-glm::normalize(s.light.direction), 0.0f);
  // The light view's right and up axes: rows 0 and 1 of its rotation.
  p.rtAxisU = glm::vec4(lightV[0][0], lightV[1][0], lightV[2][0], float(opt_.maxHits));
  p.rtAxisV = glm::vec4(lightV[0][1], lightV[1][1], lightV[2][1], perW);
  params_ = dev.createBuffer({"rt.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  walk_ = rt::uploadWalk(dev, walk, rayQuery_, "rt.", Owner::Shadow);
  status_ = dev.createBuffer({"rt.status", Owner::Shadow, BufferUsage::Storage, 16});
}

// Clears the capped-ray count before the shading passes add to it.
Pass RayTracedShadow::clearPass() const { return Pass("rt.clear").storage(kStatus, status_); }

void RayTracedShadow::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  graph.add(clearPass(), [this, &dev] { dev.fillBuffer(status_, 0); });
}

ShadowLookup RayTracedShadow::lookup() const {
  ShadowLookup l{rayQuery_ ? "techniques/rt/lookup_ray_query.glsl" : "techniques/rt/lookup.glsl"};
  // The status buffer is written by the lookup (an atomic count of capped
  // rays): a side output, which keeps no pass alive. As written storage,
  // every pass that shades through the lookup became a writer the graph kept
  // (a culled transparency technique's passes in a visibility-only run,
  // tests/test_cull_build.cpp). So the counter sums the rays of the passes
  // that ran; rt.clear zeroes it before them.
  l.inputs.uniform(kParams, params_);
  if (rayQuery_)
    l.inputs.accelerationStructure(kScene, walk_.scene);
  else
    l.inputs.readStorage(kNodes, walk_.nodes);
  l.inputs.readStorage(kSegments, walk_.segments).sideOutput(kStatus, status_);
  if (opt_.maxHits > 0) l.defines.defines.push_back({"SB_RT_COUNT_CAP", "1"});
  opaque_.addTo(l);
  return l;
}

std::vector<Counter> RayTracedShadow::counters(Device& dev) {
  const auto status = readBufferAs<uint32_t>(dev, status_);
  return {{"rt.bvh_build_ms", buildMs_},
          {"rt.bvh_nodes", double(nodeCount_)},
          {"rt.bvh_depth", double(depth_)},
          {"rt.segments", double(segmentCount_)},
          {"rt.max_hits_reached", status.empty() ? 0.0 : double(status[0])},
          {"rt.tier_ray_query", rayQuery_ ? 1.0 : 0.0}};
}

}  // namespace sb
