// The registry the scene generators' folders fill (scenes/scene_unit.h), makeScene over it,
// and what makeScene does to every scene after its unit: a uniform scale, doubled points and
// the groom.
#include "scenes/scene_unit.h"

#include <algorithm>
#include <limits>
#include <new>

#include "scenes/groom_rule.h"

namespace sb {

namespace {

UnitRegistry<SceneDescriptor>& registry() {
  static UnitRegistry<SceneDescriptor> scenes("scene", "scenes/generators/");
  return scenes;
}

// The generation rule's shape: meaningful only with guides= (applyGroom refuses them without).
std::vector<Option<SceneBase>> groomShapeOptions() {
  using SB = SceneBase;
  return opt::group<SB>(
      {opt::number(&SB::guideSpread, "guide_spread", "0.5", 0.0, 1.0,
                   "guides=: how far a strand leans to a neighbouring guide, 0..1"),
       opt::number(&SB::guideOffset, "guide_offset", "0.5", 0.0, 10.0,
                   "guides=: per-strand offset in mean guide spacings, 0..10"),
       opt::number(&SB::noise, "noise", "0.1", 0.0, 10.0,
                   "guides=: per-point noise at the tip in mean guide spacings, 0..10"),
       opt::number(&SB::clump, "clump", "0", 0.0, 1.0,
                   "guides=: pull to the home guide at the tip, 0..1")});
}

// The stiff-case options every scene has: a uniform scale and doubled points.
void applyScaleAndZeroSegments(const SceneBase& o, Scene& scene) {
  const float scale = o.scale;
  if (scale != 1.0f) {
    for (auto& p : scene.strands.points) p *= scale;
    for (auto& t : scene.strands.thickness) t *= scale;
    for (auto& p : scene.mesh.positions) p *= scale;
  }
  if (!o.zeroSegments) return;
  Strands in = std::move(scene.strands), out;
  out.thicknessFallback = in.thicknessFallback;
  reserve(out, in.strandCount(), 2 * in.points.size() / std::max<std::size_t>(1, in.strandCount()));
  for (std::size_t k = 0; k < in.strandCount(); ++k) {
    out.firstPoint.push_back(uint32_t(out.points.size()));
    out.pointCount.push_back(2 * in.pointCount[k]);
    for (uint32_t i = in.firstPoint[k]; i < in.firstPoint[k] + in.pointCount[k]; ++i)
      for (int twice = 0; twice < 2; ++twice) {
        out.points.push_back(in.points[i]);
        out.colors.push_back(in.colors[i]);
        out.thickness.push_back(in.thickness[i]);
        out.transparency.push_back(in.transparency[i]);
      }
  }
  checkTotal(o, 1, out.points.size());
  scene.strands = std::move(out);
}

// guides= and instances=: the groom kept with the scene, its strands made by the
// rule on the CPU, and the mesh repeated with every instance.
void applyGroom(const SceneBase& o, Scene& scene) {
  GroomSettings g;
  g.guideEvery = o.guides;
  g.instances = o.instances;
  g.seed = o.seed;
  g.spread = o.guideSpread;
  g.offset = o.guideOffset;
  g.noise = o.noise;
  g.clump = o.clump;
  g.lod = o.lod;
  g.lodPixels = o.lodPixels;
  // The rule's shape options mean nothing without guides: refused rather than ignored
  // (any of them off its declared default).
  static const OptionTable<SceneBase> shape({groomShapeOptions()});
  if (g.guideEvery == 0 && !shape.given(o).empty())
    throw o.error(
        "guide_spread=, guide_offset=, noise= and clump= need guides= (every n-th strand a "
        "guide)");
  if (g.lod < 1.0f && g.lodPixels > 0)
    throw o.error(
        "lod= (a fixed share) and lod_pixels= (a share by size on screen) are two "
        "levels of detail: give one");
  // The level of detail thins a groom: without guides every strand is its own.
  if (g.guideEvery == 0 && g.instances == 1 && g.lod == 1.0f && g.lodPixels == 0) return;
  scene.groom = makeGroom(scene.strands, g);
  checkTotal(o, 1, scene.groom.totalPoints());
  const bool fallback = scene.strands.thicknessFallback;
  scene.strands = generateStrands(scene.groom);
  scene.strands.thicknessFallback = fallback;
  if (g.instances == 1 || scene.mesh.positions.empty()) return;
  Mesh one = std::move(scene.mesh);
  Mesh& all = scene.mesh;
  for (const glm::vec4& place : scene.groom.placements) {
    const uint32_t base = uint32_t(all.positions.size());
    for (const glm::vec3& p : one.positions)
      all.positions.push_back(groom_rule::groomPlace(p, place));
    for (const glm::vec3& n : one.normals)
      all.normals.push_back(groom_rule::groomPlace(n, {place.x, place.y, 0.0f, 0.0f}));
    for (uint32_t i : one.indices) all.indices.push_back(base + i);
  }
}

}  // namespace

void reserve(Strands& s, std::size_t strands, std::size_t points) {
  s.firstPoint.reserve(strands);
  s.pointCount.reserve(strands);
  s.points.reserve(strands * points);
  s.colors.reserve(strands * points);
  s.thickness.reserve(strands * points);
  s.transparency.reserve(strands * points);
}

void checkTotal(const SceneBase& o, uint64_t strands, uint64_t points) {
  if (strands * points > kMaxTotalPoints) {
    throw o.error(std::to_string(strands) + " strands x " + std::to_string(points) +
                  " points = " + std::to_string(strands * points) +
                  " points exceeds the limit of " + std::to_string(kMaxTotalPoints));
  }
}

std::vector<Option<SceneBase>> alphaOptions() {
  using SB = SceneBase;
  return opt::group<SB>(
      {opt::number(&SB::alpha, "alpha", "1", 0.0, 1.0, "hair opacity in [0,1] for transparency"),
       opt::number(&SB::shadowAlpha, "shadow_alpha", "0.5", 0.0, 1.0,
                   "per-fragment shadow opacity in [0,1]")});
}

std::vector<Option<SceneBase>> seedOption(std::string help) {
  return opt::integer(&SceneBase::seed, "seed", 1, 0, std::numeric_limits<uint32_t>::max(),
                      std::move(help));
}

std::vector<Option<SceneBase>> sceneBaseOptions() {
  using SB = SceneBase;
  return opt::group<SB>(
      {opt::number(&SB::scale, "scale", "1", 1e-6, 1e6,
                   "uniform scale of the whole scene, 1e-6..1e6"),
       scene_opt::zeroOne(&SB::zeroSegments, "zero_segments", false,
                          "1: every point doubled (every other segment has zero length)"),
       // The groom every scene may have (applyGroom): guides, the generation rule's shape, a
       // crowd.
       opt::integer(&SB::guides, "guides", 0, 0, kMaxStrands,
                    "every n-th strand is a guide and the strands are made from the guides by "
                    "the generation rule (docs/geometry.md); 0: no guides"),
       groomShapeOptions(),
       scene_opt::positive(&SB::lod, "lod", "1", 1.0,
                           "level of detail: the share of each instance's strands kept (0..1], "
                           "their thickness widened by the strands left out (docs/geometry.md)"),
       opt::number(&SB::lodPixels, "lod_pixels", "0", 0.0, 100000.0,
                   "level of detail by size on screen: an instance spanning s pixels keeps "
                   "min(1, (s/lod_pixels)^2) of its strands, widened to match; 0: off"),
       opt::integer(&SB::instances, "instances", 1, 1, 10000,
                    "copies of the groom in a grid on the floor, each turned and made with its "
                    "own seed, 1..10000")});
}

SceneRegistrar::SceneRegistrar(const char* file, SceneDescriptor d) {
  if (d.help.empty() || !d.make)
    throw std::logic_error(std::string(file) + ": a scene needs a name, help and make");
  registry().add(file, std::move(d));
}

const std::vector<SceneInfo>& sceneCatalog() {
  static const std::vector<SceneInfo> catalog = [] {
    std::vector<const SceneDescriptor*> units = registry().all();  // by name
    std::stable_sort(
        units.begin(), units.end(),
        [](const SceneDescriptor* a, const SceneDescriptor* b) { return a->order < b->order; });
    std::vector<SceneInfo> c;
    for (const SceneDescriptor* d : units) c.push_back({d->name, d->help, d->options, d->folder});
    return c;
  }();
  return catalog;
}

Scene makeScene(const Spec& spec) {
  const SceneDescriptor* unit = registry().find(spec.name);
  if (!unit) {
    std::vector<std::string> names;  // in the catalog's order
    for (const SceneInfo& s : sceneCatalog()) names.push_back(s.name);
    throw InputError(unknownNameMessage("scene", spec.name, names));
  }
  const std::string what = "scene '" + unit->name + "'";
  SceneBase base;
  base.scene = unit->name;
  Scene scene;
  try {
    scene = unit->make(OptionReader(spec, unit->options, what), base);
  } catch (const UnnamedSceneError& e) {
    throw InputError(what + ": " + e.what());
  } catch (const std::bad_alloc&) {
    throw OutOfMemoryError("out of memory building scene " + spec.str() +
                           ": a host allocation failed (points, colours and segment arrays; "
                           "fewer strands= or points= make it fit)");
  }
  scene.hairAlpha = base.alpha;
  scene.shadowAlpha = base.shadowAlpha;
  applyScaleAndZeroSegments(base, scene);
  applyGroom(base, scene);
  scene.name = spec.str();
  return scene;
}

}  // namespace sb
