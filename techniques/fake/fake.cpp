#include "techniques/fake/fake.h"

#include <cstring>

#include "render/common/shader_library.h"
#include "render/shading/hair_shading.h"
#include "techniques/fake/slots.h"

namespace sb {

namespace {
constexpr uint32_t kImage0 = SB_SLOT_FAKE_IMAGE0;
}  // namespace

void FakeTransparency::setup(Device& dev, const GpuScene& scene, const RenderSettings& s,
                             const HairShading& shading, const OitTargets& targets) {
  keep(scene, s, shading, targets);

  // The subsets' segment lists: a strand's segments have consecutive first
  // points, so a new strand begins wherever the first point jumps.
  std::array<std::vector<uint32_t>, kSubsets> subsets;
  if (scene.hasHair()) {
    const std::vector<uint8_t> bytes = dev.readBuffer(scene.segments);
    std::vector<uint32_t> all(bytes.size() / sizeof(uint32_t));
    std::memcpy(all.data(), bytes.data(), all.size() * sizeof(uint32_t));
    all.resize(std::min<std::size_t>(all.size(), scene.segmentCount));
    uint32_t strand = 0;
    for (std::size_t j = 0; j < all.size(); ++j) {
      if (j > 0 && all[j] != all[j - 1] + 1) ++strand;
      subsets[strand % kSubsets].push_back(all[j]);
    }
  }
  for (uint32_t k = 0; k < kSubsets; ++k) {
    counts_[k] = static_cast<uint32_t>(subsets[k].size());
    if (subsets[k].empty()) subsets[k].push_back(0);  // a buffer is never empty; not drawn
    segments_[k] = dev.createBuffer({"fake.segments" + std::to_string(k), Owner::Oit,
                                     BufferUsage::Storage, subsets[k].size() * sizeof(uint32_t)},
                                    subsets[k].data());
    images_[k] = dev.createTexture(
        {"fake.image" + std::to_string(k), Owner::Oit, Format::RGBA32F, s.width, s.height, false});
    // --msaa N: each subset draws into N samples, averaged into its image at the
    // end of its pass; the images are premultiplied (alpha 1 where hair was
    // drawn, (0, 0, 0, 0) elsewhere), so the averages are its coverage and colour.
    if (s.msaa > 1)
      imagesMs_[k] = dev.createTexture({"fake.image" + std::to_string(k) + "_ms", Owner::Oit,
                                        Format::RGBA32F, s.width, s.height, false, 1, s.msaa});
  }
  depth_ = dev.createTexture(
      {"fake.depth", Owner::Oit, Format::Depth32F, s.width, s.height, false, 1, s.msaa});

  // Each subset: opaque hair, shaded as --oit none shades it, depth-tested.
  const ShaderCode vert = Geometry::strandVertexShader(s);
  const ShaderCode frag = loadShader("render/shading/hair.frag", shading.hairDefines());
  PipelineDesc d = subsetPass(0).pipeline(dev, "fake.subset", "fake+" + shading.shadow().name());
  d.vertex = &vert;
  d.fragment = &frag;
  d.topology = Geometry::strandTopology(s);
  d.depthCompare = CompareOp::Less;
  hairPipeline_ = dev.createPipeline(d);
  if (scene.hasMesh()) {
    const ShaderCode meshVert = Geometry::meshVertexShader();
    const ShaderCode meshFrag = loadShader("techniques/fake/mesh.frag");
    d.name = "fake.mesh";
    d.vertex = &meshVert;
    d.fragment = &meshFrag;
    d.topology = Topology::Triangles;
    meshPipeline_ = dev.createPipeline(d);
  }

  // The blend: C = hair + (1 - coverage) C_dst; the destination alpha kept.
  const ShaderCode fullScreen = loadShader("render/common/composite.vert");
  const ShaderCode blend = loadShader("techniques/fake/blend.frag");
  PipelineDesc b = blendPass().pipeline(dev, "fake.blend", "fake");
  b.vertex = &fullScreen;
  b.fragment = &blend;
  b.depthTest = b.depthWrite = false;  // the pass only clears the frame depth, if it has one
  b.blend = {{true, BlendFactor::One, BlendFactor::SrcAlpha, BlendOp::Add, BlendFactor::Zero,
              BlendFactor::One, BlendOp::Add}};
  blendPipeline_ = dev.createPipeline(b);
}

// Subset k into its own image, cleared to (0, 0, 0, 0), with its own depth.
Pass FakeTransparency::subsetPass(uint32_t k) const {
  Inputs in = shading_->hairInputs();
  in.replaceBuffer(bind::kSegments, segments_[k]);
  Pass p("fake.subset" + std::to_string(k));
  if (imagesMs_[k])
    p.color(imagesMs_[k], LoadOp::Clear, {0, 0, 0, 0}).resolveInto(images_[k]);
  else
    p.color(images_[k], LoadOp::Clear, {0, 0, 0, 0});
  return p.depth(depth_, LoadOp::Clear).inputs(in);
}

// Nothing opaque drawn: the blend also clears the frame's depth to 1, as the
// other blending techniques leave it (the hair writes no frame depth).
Pass FakeTransparency::blendPass() const {
  Pass p("fake.blend");
  p.colorOver(targets_.color, targets_.opaqueDrawn, settings_.background);
  if (targets_.resolved) p.resolveInto(targets_.resolved);  // --msaa: the samples averaged
  if (!targets_.opaqueDrawn) p.depth(targets_.depth, LoadOp::Clear);
  for (uint32_t k = 0; k < kSubsets; ++k) p.sample(kImage0 + k, images_[k]);
  return p;
}

void FakeTransparency::addPasses(FrameGraph& graph, Device& dev) {
  const uint32_t perSegment =
      Geometry::strandVertexCount(*scene_, settings_) / std::max(scene_->segmentCount, 1u);
  for (uint32_t k = 0; k < kSubsets; ++k) {
    graph.add(subsetPass(k), [this, &dev, k, perSegment, p = subsetPass(k)] {
      std::vector<Pass::Draw> draws;
      if (meshPipeline_) draws.push_back({meshPipeline_, scene_->meshTriangles * 3});
      if (counts_[k] > 0) draws.push_back({hairPipeline_, counts_[k] * perSegment});
      p.draw(dev, draws);
    });
  }
  graph.add(blendPass(), [this, &dev, p = blendPass()] { p.draw(dev, blendPipeline_, 3); });
}

}  // namespace sb
