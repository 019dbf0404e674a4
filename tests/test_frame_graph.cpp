// A pass declared once (render/graph/pass.h) gives its pipeline slots,
// draw bindings, device pass and graph edges; the frame graph culls nodes no
// output needs and rejects a texture read that no earlier node writes.
// Handles here are plain ids: declaring passes and compiling needs no device.
#include <gtest/gtest.h>

#include <map>

#include "render/graph/frame_graph.h"

namespace sb {
namespace {

// Distinct ids, as the Device hands them out (one id space for all kinds).
const Texture kMap{1}, kExtra{2}, kColor{3}, kDepth{4}, kTypo{9};
const Buffer kParams{5}, kLists{6}, kScene{7};

std::vector<std::string> names(const std::vector<const PassNode*>& nodes) {
  std::vector<std::string> out;
  for (const auto* n : nodes) out.push_back(n->name);
  return out;
}

FrameGraph::Namer namer() {
  static const std::map<uint32_t, std::string> kNames = {
      {1, "shadow.map"}, {2, "debug.image"}, {3, "frame.color"}, {9, "shadow.mpa"}};
  return [](GraphResource r) { return kNames.at(r.id); };
}

// shadow -> map; unused -> extra; shading samples `shadingSamples`, writes colour.
FrameGraph shadowAndShading(Texture shadingSamples) {
  FrameGraph g(namer());
  g.add(Pass("shadow.depth").depth(kMap, LoadOp::Clear), [] {});
  g.add(Pass("shadow.unused").color(kExtra, LoadOp::Clear), [] {});
  g.add(Pass("shading").color(kColor, LoadOp::Clear).sample(9, shadingSamples), [] {});
  return g;
}

TEST(FrameGraph, KeepsOnlyWhatTheOutputsNeed) {
  const FrameGraph g = shadowAndShading(kMap);
  EXPECT_EQ(names(g.compile({GraphResource::of(kColor)})),
            (std::vector<std::string>{"shadow.depth", "shading"}));
  EXPECT_EQ(names(g.compile({GraphResource::of(kExtra)})),
            std::vector<std::string>{"shadow.unused"});
  EXPECT_TRUE(g.compile({GraphResource::of(kTypo)}).empty());
}

// A side output (a counter the shading adds to): its writer is not kept for
// it, the pass that clears it is kept before a writer that is kept. Can fail:
// the same counter as plain storage keeps the unneeded writer alive.
TEST(FrameGraph, ASideOutputKeepsNoWriterAliveAndKeepsItsClear) {
  const Buffer counter{8};
  auto graph = [&](bool side) {
    FrameGraph g;
    g.add(Pass("clear").storage(0, counter), [] {});
    Pass unused("unused");
    unused.color(kExtra, LoadOp::Clear);
    Pass shading("shading");
    shading.color(kColor, LoadOp::Clear);
    for (Pass* p : {&unused, &shading}) {
      p->inputs(side ? Inputs().sideOutput(1, counter) : Inputs().storage(1, counter));
      g.add(*p, [] {});
    }
    return g;
  };
  const FrameGraph side = graph(true);
  EXPECT_EQ(names(side.compile({GraphResource::of(kColor)})),
            (std::vector<std::string>{"clear", "shading"}));
  EXPECT_EQ(side.nodes()[2].sideWrites, std::vector<GraphResource>{GraphResource::of(counter)});
  EXPECT_TRUE(side.nodes()[2].writes.size() == 1);                          // the colour only
  EXPECT_EQ(graph(false).compile({GraphResource::of(kColor)}).size(), 3u);  // "unused" kept
}

TEST(FrameGraph, ATextureReadNothingWritesIsRejectedNamingPassAndResource) {
  const FrameGraph g = shadowAndShading(kTypo);  // the wrong texture
  try {
    g.compile({GraphResource::of(kColor)});
    FAIL() << "compiled a read that nothing writes";
  } catch (const std::logic_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("pass 'shading'"), std::string::npos) << m;
    EXPECT_NE(m.find("'shadow.mpa'"), std::string::npos) << m;
  }
}

TEST(FrameGraph, AReadOfALaterWriteIsRejected) {
  FrameGraph g(namer());
  g.add(Pass("first").color(kColor, LoadOp::Clear).sample(9, kMap), [] {});
  g.add(Pass("second").depth(kMap, LoadOp::Clear), [] {});
  EXPECT_THROW(g.compile({GraphResource::of(kColor)}), std::logic_error);
}

TEST(FrameGraph, ABufferNothingWritesIsAnInputFromTheCpu) {
  FrameGraph g;
  g.add(Pass("draw").color(kColor, LoadOp::Clear).uniform(0, kParams).readStorage(2, kScene),
        [] {});
  EXPECT_EQ(names(g.compile({GraphResource::of(kColor)})), std::vector<std::string>{"draw"});
}

TEST(FrameGraph, EdgesFollowTheDeclaration) {
  // A loaded attachment is read, a read-only depth is not written, storage is
  // read and written, read-only storage only read.
  const Pass p = Pass("hair")
                     .color(kColor, LoadOp::Load)
                     .depthReadOnly(kDepth)
                     .storage(16, kLists)
                     .readStorage(2, kScene)
                     .sample(9, kMap);
  auto has = [](const std::vector<GraphResource>& v, uint32_t id) {
    return std::find(v.begin(), v.end(), GraphResource{id, false}) != v.end();
  };
  const auto reads = p.reads(), writes = p.writes();
  for (uint32_t id : {kColor.id, kDepth.id, kLists.id, kScene.id, kMap.id})
    EXPECT_TRUE(has(reads, id)) << id;
  EXPECT_TRUE(has(writes, kColor.id));
  EXPECT_TRUE(has(writes, kLists.id));
  EXPECT_FALSE(has(writes, kDepth.id));
  EXPECT_FALSE(has(writes, kScene.id));
  EXPECT_FALSE(has(writes, kMap.id));
  // A cleared attachment is written, not read.
  EXPECT_FALSE(has(Pass("c").color(kColor, LoadOp::Clear).reads(), kColor.id));
}

TEST(FrameGraph, APassGivesSlotsBindingsAndTheDevicePassFromOneDeclaration) {
  const Pass p = Pass("dom.opacity")
                     .color(kExtra, LoadOp::Load, {0, 0, 0, 0}, 0)
                     .color(kExtra, LoadOp::Clear, {0, 0, 0, 0}, 1)
                     .uniform(8, kParams)
                     .sample(9, kMap)
                     .sampleArray(10, kColor);
  const auto slots = p.slots();
  ASSERT_EQ(slots.size(), 3u);
  EXPECT_EQ(slots[0].binding, 8u);
  EXPECT_EQ(slots[0].kind, BindingKind::UniformBuffer);
  EXPECT_EQ(slots[1].kind, BindingKind::SampledTexture);
  EXPECT_EQ(slots[2].kind, BindingKind::SampledTextureArray);
  const auto b = p.bindings();
  ASSERT_EQ(b.size(), 3u);
  EXPECT_EQ(b[0].buffer.id, kParams.id);
  EXPECT_EQ(b[1].texture.id, kMap.id);
  const PassDesc d = p.desc();
  EXPECT_EQ(d.name, "dom.opacity");
  ASSERT_EQ(d.color.size(), 2u);
  EXPECT_EQ(d.color[1].layer, 1u);
  ASSERT_EQ(d.sampledTextures.size(), 2u);  // every sampled texture, declared once
  EXPECT_EQ(d.sampledTextures[0].id, kMap.id);
}

TEST(FrameGraph, ANodeOfSeveralPassesKeepsItsInnerReadsInside) {
  // As dc.iterate: the means read what the iteration wrote, inside one node.
  const Texture range{1}, centres{2}, sums{3};
  FrameGraph g;
  g.add(Pass("init").color(range, LoadOp::Clear), [] {});
  const Pass first = Pass("means.first").color(centres, LoadOp::Clear).sample(9, range);
  const Pass iterate = Pass("iterate").color(sums, LoadOp::Clear).sampleArray(13, centres);
  const Pass means = Pass("means").color(centres, LoadOp::Clear).sampleArray(11, sums);
  g.add("iterate", {first, iterate, means}, [] {});
  const auto kept = g.compile({GraphResource::of(sums)});
  EXPECT_EQ(names(kept), (std::vector<std::string>{"init", "iterate"}));
  EXPECT_EQ(kept[1]->reads.size(), 1u);  // only the range, from outside
}

}  // namespace
}  // namespace sb
