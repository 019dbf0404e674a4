#include "techniques/compute_raster/compute_raster.h"

#include <algorithm>
#include <cstring>

#include "base/errors.h"
#include "base/options.h"
#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"
#include "techniques/compute_raster/slots.h"
#include "techniques/compute_raster/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kCursor = SB_SLOT_CRASTER_CURSOR, kLayout = SB_SLOT_CRASTER_LAYOUT,
                   kFragments = SB_SLOT_CRASTER_FRAGMENTS, kShaded = SB_SLOT_CRASTER_SHADED,
                   kOpaque = SB_SLOT_CRASTER_OPAQUE, kParams = SB_SLOT_CRASTER_PARAMS,
                   kBuckets = SB_SLOT_CRASTER_BUCKETS, kRanges = SB_SLOT_CRASTER_RANGES;
constexpr std::size_t kFragmentBytes = 16;
// The status words at the head of the cursor buffer (compute_raster.glsl).
enum Status : uint32_t {
  kGenerated = 0,
  kDropped,
  kOverflowed,
  kMaxTile,
  kSegments,
  kTerminated,
  kStatusWords = 8
};
}  // namespace

void ComputeRasterOit::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                             const HairShading& shading, const OitTargets& targets) {
  keepInputs(dev, scene, s, shading, targets);
  tilesX_ = (s.width + o_.tile - 1) / o_.tile;
  tilesY_ = (s.height + o_.tile - 1) / o_.tile;

  // Its own option thickness=on draws world widths with its coverage model.
  if (s.primitive == Primitive::World)
    throw InputError(
        "transparency technique 'compute_raster': --primitive world is not "
        "supported (its option thickness=on draws the strands' world widths)");
  const float frameWidth = s.primitive == Primitive::Ribbons ? s.ribbonWidth : 1.0f;
  CRasterParams p{};
  p.crTiles = glm::uvec4(tilesX_, tilesY_, o_.tile, tiles());
  p.crSize = glm::uvec4(s.width, s.height, 0, 0);
  p.crStrand = glm::vec4(o_.width > 0 ? o_.width : frameWidth, 0, 0, o_.terminate);
  p.crModel = glm::uvec4(o_.analytic ? 0u : 1u, s.primitive == Primitive::Lines ? 1u : 0u,
                         scene.segmentCount, o_.thickness ? 1u : 0u);
  // Pixels per world unit at clip w = 1: half the viewport times the length of
  // the view-projection's x row (the view is rigid: the projection's x scale).
  const glm::mat4 vp = cameraView(s).viewProj;
  const float xScale = glm::length(glm::vec3(vp[0][0], vp[1][0], vp[2][0]));
  p.crWidth = glm::vec4(0.5f * float(s.width) * xScale, 0, 0, 0);
  params_ =
      dev.createBuffer({name() + ".params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);
  cursor_ = dev.createBuffer(
      {name() + ".cursor", Owner::Oit, BufferUsage::Storage, (kStatusWords + tiles()) * 4ull});
  if (o_.fragments > 0) {
    // The engines' fixed layout: every tile owns `fragments` entries.
    if (uint64_t(tiles()) * o_.fragments > 0xFFFFFFFFull)
      throw InputError("compute_raster: " + std::to_string(tiles()) +
                       " tiles x fragments=" + std::to_string(o_.fragments) +
                       " entries do not fit one pool of 2^32 entries; lower fragments=");
    std::vector<glm::uvec2> layout(tiles());
    for (uint32_t t = 0; t < tiles(); ++t) layout[t] = {t * o_.fragments, o_.fragments};
    pool_ = uint64_t(tiles()) * o_.fragments;
    layout_ = dev.createBuffer(
        {name() + ".layout", Owner::Oit, BufferUsage::Storage, layout.size() * sizeof(glm::uvec2)},
        layout.data());
  } else {
    layout_ = dev.createBuffer(
        {name() + ".layout", Owner::Oit, BufferUsage::Storage, tiles() * sizeof(glm::uvec2)});
  }
  fragments_ = dev.createBuffer({name() + ".fragments", Owner::Oit, BufferUsage::Storage,
                                 std::max<uint64_t>(pool_, 1) * kFragmentBytes});
  buckets_ = dev.createBuffer({name() + ".buckets", Owner::Oit, BufferUsage::Storage,
                               std::max<uint64_t>(pool_, 1) * kFragmentBytes});
  ranges_ = dev.createBuffer(
      {name() + ".ranges", Owner::Oit, BufferUsage::Storage, std::size_t(s.width) * s.height * 8});
  if (o_.perPoint)
    shaded_ = dev.createBuffer({name() + ".shaded", Owner::Oit, BufferUsage::Storage,
                                std::max<std::size_t>(scene.segmentCount, 1) * 2 * 16});

  ShaderDefines raster;
  if (targets.opaqueDrawn) raster.defines.push_back({"SB_CRASTER_OPAQUE", "1"});
  auto compute = [&dev](const Pass& pass, const std::string& pipelineName,
                        const std::string& technique, const std::string& file,
                        const ShaderDefines& defs) {
    const ShaderCode comp = loadShader(file, defs);
    PipelineDesc d = pass.pipeline(dev, pipelineName, technique);
    d.compute = &comp;
    return dev.createPipeline(d);
  };
  const std::string shaded = name() + "+" + shading.shadow().name();
  raster_ = compute(rasterPass(), name() + ".raster", name(),
                    "techniques/compute_raster/raster.comp", raster);
  if (o_.fragments == 0) {
    ShaderDefines count = raster;
    count.defines.push_back({"SB_CRASTER_COUNT", "1"});
    count_ = compute(countPass(), name() + ".count", name(),
                     "techniques/compute_raster/raster.comp", count);
  }
  if (o_.perPoint)
    shade_ = compute(shadePass(), name() + ".shade", shaded, "techniques/compute_raster/shade.comp",
                     shading.hairDefines());
  // The shading's defines either way: the loader resolves <shadow> in the
  // per-fragment branch too, which the preprocessor then drops.
  // The shading's defines in both: the loader resolves <shadow> in the
  // per-fragment branch too, which the preprocessor then drops.
  ShaderDefines bucket = shading.hairDefines();
  bucket.defines.push_back({"SB_CRASTER_TILE", std::to_string(o_.tile)});
  bucket.defines.push_back({"SB_CRASTER_BUCKET", "1"});
  bucket_ = compute(bucketPass(), name() + ".bucket", name(),
                    "techniques/compute_raster/resolve.comp", bucket);
  ShaderDefines resolve = shading.hairDefines();
  resolve.defines.push_back({"SB_CRASTER_TILE", std::to_string(o_.tile)});
  if (!o_.perPoint) resolve.defines.push_back({"SB_CRASTER_PER_FRAGMENT", "1"});
  resolve_ = compute(resolvePass(), name() + ".resolve", o_.perPoint ? name() : shaded,
                     "techniques/compute_raster/resolve.comp", resolve);
}

void ComputeRasterOit::prepare(Device& dev) {
  // Counts every tile's fragments (one frame of the raster pass, counting only)
  // and gives each tile exactly that many entries of one pool.
  dev.fillBuffer(cursor_, 0);
  if (scene_->segmentCount > 0) {
    dev.beginFrame();
    const glm::uvec2 g = dispatchGroups(scene_->segmentCount);
    countPass().dispatch(dev, count_, g.x, g.y);
    dev.endFrame();
  }
  const auto bytes = dev.readBuffer(cursor_);
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  std::vector<glm::uvec2> layout(tiles());
  uint64_t offset = 0;
  for (uint32_t t = 0; t < tiles(); ++t) {
    const uint32_t n = words[kStatusWords + t];
    layout[t] = {static_cast<uint32_t>(offset), n};
    offset += n;
  }
  if (offset > 0xFFFFFFFFull)
    throw InputError("compute_raster: " + std::to_string(offset) +
                     " fragments do not fit one pool of 2^32 entries; lower the resolution or "
                     "give fragments=N per tile");
  pool_ = offset;
  dev.updateBuffer(layout_, layout.data(), layout.size() * sizeof(glm::uvec2));
  dev.setBufferSize(fragments_, std::max<uint64_t>(pool_, 1) * kFragmentBytes);
  dev.setBufferSize(buckets_, std::max<uint64_t>(pool_, 1) * kFragmentBytes);
}

Pass ComputeRasterOit::shadePass() const {
  return Pass(name() + ".shade")
      .inputs(shading_->hairInputs())
      .uniform(kParams, params_)
      .storage(kShaded, shaded_);
}

Pass ComputeRasterOit::countPass() const {
  Pass p(name() + ".count");
  p.inputs(Geometry::inputs(*scene_, shading_->viewUbo()))
      .uniform(kParams, params_)
      .storage(kCursor, cursor_);
  if (targets_.opaqueDrawn) p.sample(kOpaque, targets_.depth);
  return p;
}

Pass ComputeRasterOit::rasterPass() const {
  Pass p(name() + ".raster");
  p.inputs(Geometry::inputs(*scene_, shading_->viewUbo()))
      .uniform(kParams, params_)
      .storage(kCursor, cursor_)
      .readStorage(kLayout, layout_)
      .storage(kFragments, fragments_);
  if (targets_.opaqueDrawn) p.sample(kOpaque, targets_.depth);
  return p;
}

Pass ComputeRasterOit::bucketPass() const {
  return Pass(name() + ".bucket")
      .uniform(kParams, params_)
      .storage(kCursor, cursor_)
      .readStorage(kLayout, layout_)
      .storage(kFragments, fragments_)
      .storage(kBuckets, buckets_)
      .storage(kRanges, ranges_);
}

Pass ComputeRasterOit::resolvePass() const {
  Pass p(name() + ".resolve");
  if (o_.perPoint)
    p.readStorage(kShaded, shaded_);
  else
    p.inputs(shading_->hairInputs());
  return p.uniform(kParams, params_)
      .storage(kCursor, cursor_)
      .readStorage(kLayout, layout_)
      .readStorage(kFragments, fragments_)
      .readStorage(kBuckets, buckets_)
      .readStorage(kRanges, ranges_)
      .storage(AccumComposite::kAccumBinding, composite_.accum());
}

void ComputeRasterOit::addPasses(FrameGraph& graph, Device& dev) {
  std::vector<Pass> passes;
  if (o_.perPoint) passes.push_back(shadePass());
  passes.push_back(rasterPass());
  passes.push_back(bucketPass());
  passes.push_back(resolvePass());
  passes.push_back(composite_.pass());
  graph.add(name(), passes, [this, &dev] {
    dev.fillBuffer(cursor_, 0);
    if (scene_->segmentCount > 0) {
      const glm::uvec2 g = dispatchGroups(scene_->segmentCount);
      if (o_.perPoint) shadePass().dispatch(dev, shade_, g.x, g.y);
      rasterPass().dispatch(dev, raster_, g.x, g.y);
    }
    bucketPass().dispatch(dev, bucket_, tilesX_, tilesY_);
    resolvePass().dispatch(dev, resolve_, tilesX_, tilesY_);
    composite_.record(dev);
  });
}

std::vector<uint32_t> ComputeRasterOit::status(Device& dev) {
  const auto bytes = dev.readBuffer(cursor_);
  std::vector<uint32_t> words(kStatusWords, 0);
  std::memcpy(words.data(), bytes.data(), std::min<std::size_t>(bytes.size(), kStatusWords * 4));
  return words;
}

std::vector<Counter> ComputeRasterOit::counters(Device& dev) {
  const std::vector<uint32_t> s = status(dev);
  return {{"tiles", double(tiles())},
          {"pool_fragments", double(pool_)},
          {"fragments", double(s[kGenerated])},
          {"dropped_fragments", double(s[kDropped])},
          {"overflowed_tiles", double(s[kOverflowed])},
          {"max_tile_fragments", double(s[kMaxTile])},
          {"segments_drawn", double(s[kSegments])},
          {"pixels_terminated_early", double(s[kTerminated])}};
}

std::vector<std::string> ComputeRasterOit::warnings(Device& dev) {
  const std::vector<uint32_t> s = status(dev);
  if (s[kDropped] == 0) return {};
  const std::string capacity = o_.fragments > 0
                                   ? "fragments=" + std::to_string(o_.fragments) + " per tile"
                                   : "the counted fragments per tile";
  return {"compute_raster: tile list overflow: " + std::to_string(s[kDropped]) + " of " +
          std::to_string(s[kGenerated]) + " fragments dropped in " +
          std::to_string(s[kOverflowed]) + " tiles (" + capacity + "; the fullest tile had " +
          std::to_string(s[kMaxTile]) + ")"};
}

}  // namespace sb
