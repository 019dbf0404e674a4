#include "techniques/osm/osm.h"

#include <cmath>

#include "base/options.h"
#include "render/common/opacity.h"
#include "render/common/opacity_filter.h"
#include "render/common/shader_library.h"
#include "techniques/osm/pass_uniforms.h"
#include "techniques/osm/slicing.h"
#include "techniques/osm/slots.h"
#include "techniques/osm/uniforms.h"

namespace sb {

namespace {
constexpr uint32_t kParams = SB_SLOT_OSM_PARAMS, kPass = SB_SLOT_OSM_PASS,
                   kAtlases = SB_SLOT_OSM_ATLASES;

Format mapFormat(uint32_t bits) {
  return bits == 8 ? Format::RGBA8 : bits == 16 ? Format::RGBA16F : Format::RGBA32F;
}
}  // namespace

OpacityShadowMaps::Layout OpacityShadowMaps::layoutFor(uint32_t maps, bool multi, uint32_t size) {
  Layout l;
  l.groups = (maps + 3) / 4;
  if (!multi) {
    l.atlases = 1;
  } else {
    // Prefer a number of targets that divides the groups (no unused tiles).
    const uint32_t most = std::min(kMaxTargets, l.groups);
    l.atlases = 1;
    for (uint32_t a = most; a >= 1; --a)
      if (l.groups % a == 0) {
        l.atlases = a;
        break;
      }
    if (l.atlases * 2 < most) l.atlases = most;
  }
  l.tiles = (l.groups + l.atlases - 1) / l.atlases;
  // A grid of exactly `tiles` tiles, closest to square, within the size limit;
  // else a square-ish grid with unused tiles.
  const uint32_t limit = kMaxAtlasSize / std::max(size, 1u);
  for (uint32_t rows = 1; rows * rows <= l.tiles; ++rows)
    if (l.tiles % rows == 0 && l.tiles / rows <= limit && rows <= limit) {
      l.rows = rows;
      l.cols = l.tiles / rows;
    }
  if (l.rows == 0) {
    l.cols = static_cast<uint32_t>(std::ceil(std::sqrt(double(l.tiles))));
    l.rows = (l.tiles + l.cols - 1) / l.cols;
  }
  if (l.cols > limit || l.rows > limit)
    throw InputError("shadow technique 'osm': " + std::to_string(maps) + " maps of " +
                     std::to_string(size) + "x" + std::to_string(size) +
                     " do not fit in atlases of at most " + std::to_string(kMaxAtlasSize) +
                     " pixels a side (use fewer maps, a smaller size or passes=multi)");
  return l;
}

OpacityShadowMaps::OpacityShadowMaps(const Options& o)
    : opt_(o), layout_(layoutFor(o.maps, o.multi, o.size)) {}

void OpacityShadowMaps::setup(Device& dev, const GpuScene& scene, const RenderSettings& s) {
  const ViewUniforms view = setupLight(dev, scene, s, opt_.size);

  // Slices between the hair's near and far depth from the light, computed on
  // the CPU from the hair points projected into light space (exact for lines
  // and ribbons, whose depth is linear between their end points).
  const int n = static_cast<int>(opt_.maps);
  slices_ = osmSlices(n, opt_.slicing, opt_.gamma, hairLightDistances(dev, scene, view.viewProj));

  // Weight per fragment: counts for float maps; with 8 bits the paper's
  // scaling e^-kappa = 2^-8 at opacity 1, w = -ln(1 - alpha_s) / kappa,
  // rounded to whole unorm steps so every backend adds the same amount.
  weight_ = 1.0f;
  if (opt_.bits == 8) {
    const float kappa = opt_.kappa > 0.0f ? opt_.kappa : 8.0f * std::log(2.0f);
    const float a = scene.shadowAlpha;
    const float w = a >= 1.0f ? 1.0f : -std::log1p(-std::max(a, 0.0f)) / kappa;
    weight_ = std::clamp(std::round(w * 255.0f), 1.0f, 255.0f) / 255.0f;
  }

  OsmParams p{};
  p.osmViewProj = view.viewProj;
  p.osmParams = glm::vec4(opt_.bias, float(opt_.size), scene.shadowAlpha, weight_);
  p.osmLayout = glm::ivec4(int(layout_.cols), n, int(layout_.atlases), opt_.filter);
  for (int i = 0; i <= n; ++i) p.osmSlices[i / 4][i % 4] = slices_[std::size_t(i)];
  params_ = dev.createBuffer({"osm.params", Owner::Frame, BufferUsage::Uniform, sizeof p}, &p);

  const Format format = mapFormat(opt_.bits);
  const uint32_t w = layout_.cols * opt_.size, h = layout_.rows * opt_.size;
  atlases_ = dev.createTexture({"osm.maps", Owner::Shadow, format, w, h, false, layout_.atlases});

  // The light's view pointed at each tile: x' = x / cols + offset, so tile
  // pixels are the map's pixels shifted by whole tiles.
  for (uint32_t t = 0; t < layout_.tiles; ++t) {
    const float cols = float(layout_.cols), rows = float(layout_.rows);
    glm::mat4 m(1.0f);
    m[0][0] = 1.0f / cols;
    m[1][1] = 1.0f / rows;
    m[3][0] = (2.0f * float(t % layout_.cols) + 1.0f) / cols - 1.0f;
    m[3][1] = (2.0f * float(t / layout_.cols) + 1.0f) / rows - 1.0f;
    ViewUniforms tv = view;
    tv.viewProj = m * view.viewProj;
    tv.viewViewport = glm::vec4(float(w), float(h), s.ribbonWidth, 0.0f);
    tileViews_.push_back(dev.createBuffer(
        {"osm.tile_view" + std::to_string(t), Owner::Frame, BufferUsage::Uniform, sizeof tv}, &tv));
  }

  auto tileRect = [&](uint32_t t) {
    const float x = float(t % layout_.cols * opt_.size), y = float(t / layout_.cols * opt_.size);
    return glm::vec4(x, y, x + float(opt_.size), y + float(opt_.size));
  };
  auto addPass = [&](uint32_t targets, uint32_t tile, bool clear, glm::ivec4 range) {
    const OsmPass pp{range, tileRect(tile)};
    MapPass mp{targets, tile, clear, {}};
    mp.params = dev.createBuffer({"osm.pass" + std::to_string(passes_.size()), Owner::Frame,
                                  BufferUsage::Uniform, sizeof pp},
                                 &pp);
    passes_.push_back(mp);
  };
  if (opt_.multi) {
    // Pass p fills tile p of every atlas: groups p*atlases + k, 4 maps each.
    for (uint32_t t = 0; t < layout_.tiles; ++t) {
      const uint32_t first = t * layout_.atlases;
      if (first >= layout_.groups) break;
      const uint32_t targets = std::min(layout_.atlases, layout_.groups - first);
      addPass(targets, t, t == 0,
              glm::ivec4(int(first), int(first * 4),
                         int(std::min(opt_.maps, (first + targets) * 4)), 0));
    }
  } else {
    // The original: one pass per map, into its channel of its tile.
    for (uint32_t m = 0; m < opt_.maps; ++m)
      addPass(1, m / 4, m == 0, glm::ivec4(int(m / 4), int(m), int(m + 1), 0));
  }

  if (!scene.hasHair()) return;
  const ShaderCode vert = Geometry::strandVertexShader(s);
  pipelines_.resize(layout_.atlases);
  for (const MapPass& mp : passes_) {
    Pipeline& pipe = pipelines_[mp.targets - 1];
    if (pipe) continue;
    ShaderDefines defs;
    defs.defines.push_back({"SB_OSM_TARGETS", std::to_string(mp.targets)});
    const ShaderCode frag = loadShader("techniques/osm/map.frag", defs);
    PipelineDesc d = mapPass(mp).pipeline(dev, "osm.map" + std::to_string(mp.targets), "osm");
    d.vertex = &vert;
    d.fragment = &frag;
    d.topology = Geometry::strandTopology(s);
    d.blend.assign(mp.targets, BlendState::additive());
    pipe = dev.createPipeline(d);
  }
}

// One map pass: its targets (atlas layers), the light pointed at its tile.
Pass OpacityShadowMaps::mapPass(const MapPass& mp) const {
  Pass p("osm.map");
  for (uint32_t k = 0; k < mp.targets; ++k)
    p.color(atlases_, mp.clear ? LoadOp::Clear : LoadOp::Load, {0, 0, 0, 0}, k);
  return p.inputs(Geometry::inputs(*scene_, tileViews_[mp.tile]))
      .uniform(kParams, params_)
      .uniform(kPass, mp.params);
}

void OpacityShadowMaps::addPasses(FrameGraph& graph, Device& dev) {
  opaque_.addPass(graph, dev);
  std::vector<Pass> passes;
  for (const MapPass& mp : passes_) passes.push_back(mapPass(mp));
  graph.add("osm.map", passes, [this, &dev, passes] {
    const uint32_t vertices = Geometry::strandVertexCount(*scene_, settings_);
    for (std::size_t i = 0; i < passes.size(); ++i) {
      const uint32_t targets = passes_[i].targets;
      passes[i].draw(dev, scene_->hasHair() ? pipelines_[targets - 1] : Pipeline{}, vertices);
    }
  });
}

ShadowLookup OpacityShadowMaps::lookup() const {
  ShadowLookup l{"techniques/osm/lookup.glsl"};
  l.inputs.uniform(kParams, params_).sampleArray(kAtlases, atlases_);
  opaque_.addTo(l);
  return l;
}

}  // namespace sb
