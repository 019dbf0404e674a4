// The frame graph culls passes no output needs and rejects a read that no pass
// writes (a misspelled name would otherwise cull its writer without a word).
#include <gtest/gtest.h>

#include "techniques/common/frame_graph.h"

namespace sb {
namespace {

std::vector<std::string> names(const std::vector<const PassNode*>& passes) {
  std::vector<std::string> out;
  for (const auto* p : passes) out.push_back(p->name);
  return out;
}

FrameGraph shadowAndShading(const std::string& shadingReads) {
  FrameGraph g;
  g.add({"shadow.depth", {}, {"shadow.map"}, [] {}});
  g.add({"shadow.unused", {}, {"shadow.extra"}, [] {}});
  g.add({"shading", {shadingReads}, {"color"}, [] {}});
  return g;
}

TEST(FrameGraph, KeepsOnlyWhatTheOutputsNeed) {
  const FrameGraph g = shadowAndShading("shadow.map");
  EXPECT_EQ(names(g.compile({"color"})), (std::vector<std::string>{"shadow.depth", "shading"}));
  EXPECT_EQ(names(g.compile({"shadow.extra"})), std::vector<std::string>{"shadow.unused"});
}

TEST(FrameGraph, AReadNothingWritesIsRejectedNamingPassAndResource) {
  const FrameGraph g = shadowAndShading("shadow.mpa");  // misspelled
  try {
    g.compile({"color"});
    FAIL() << "compiled a read that nothing writes";
  } catch (const std::logic_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("pass 'shading'"), std::string::npos) << m;
    EXPECT_NE(m.find("'shadow.mpa'"), std::string::npos) << m;
  }
}

TEST(FrameGraph, AReadOfALaterWriteIsRejected) {
  FrameGraph g;
  g.add({"first", {"late"}, {"a"}, [] {}});
  g.add({"second", {}, {"late"}, [] {}});
  EXPECT_THROW(g.compile({"a"}), std::logic_error);
}

}  // namespace
}  // namespace sb
