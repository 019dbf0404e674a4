// The exact shadow's node pool split into pages (techniques/exact/nodes.glsl) gives the unsplit
// image, pixel for pixel, for exact and for the techniques built on its lists (dsm, avsm), on
// both APIs; a pool over every page bound is refused.
#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>

#include "harness/render.h"
#include "render_request.h"

namespace sb {
namespace {

std::size_t bytesOf(const RenderResult& r, const std::string& name) {
  for (const auto& x : r.resources)
    if (x.name == name) return x.bytes;
  return 0;
}

// SB_POOL_PAGE_BYTES (poolPageShift's test hook) while it lives.
struct PageBytes {
  explicit PageBytes(std::size_t bytes) {
    ::setenv("SB_POOL_PAGE_BYTES", std::to_string(bytes).c_str(), 1);
  }
  ~PageBytes() { ::unsetenv("SB_POOL_PAGE_BYTES"); }
};

const std::string kScene = "straight:strands=40,points=6,head=1,alpha=0.5,shadow_alpha=0.3";

// Forced by SB_POOL_PAGE_BYTES, the pool splits into 2 or 3 pages (the smallest
// pages that 3 bindings hold): the nodes are the unsplit ones, so is the image.
TEST(ExactPaging, ANodePoolSplitIntoPagesGivesTheSameImage) {
  for (const std::string backend : {"gl", "vulkan"}) {
    for (const std::string shadow : {"exact:size=64", "dsm:size=64", "avsm:size=64"}) {
      SCOPED_TRACE(backend + " " + shadow);
      const RenderRequest req = sbtest::smallRender(backend, kScene, shadow, "none", 24);
      const RenderResult whole = runRender(req);
      const std::size_t nodes = bytesOf(whole, "exact.nodes") / 8;
      ASSERT_GT(nodes, 64u);
      EXPECT_EQ(bytesOf(whole, "exact.nodes.page1"), 8u);  // unused: 8 bytes
      const std::size_t page = std::bit_ceil((nodes + 2) / 3);
      RenderResult split;
      {
        PageBytes hook(page * 8);
        split = runRender(req);
      }
      // It split: the first pages are full, the last holds the rest.
      std::size_t pages = 0, bytes = 0;
      for (const std::string name : {"exact.nodes", "exact.nodes.page1", "exact.nodes.page2"}) {
        const std::size_t b = bytesOf(split, name);
        if (b > 8 || name == "exact.nodes") ++pages, bytes += b;
      }
      EXPECT_EQ(bytesOf(split, "exact.nodes"), page * 8);
      EXPECT_GE(pages, 2u);
      EXPECT_EQ(bytes, nodes * 8);
      EXPECT_EQ(split.warnings, whole.warnings);
      ASSERT_FALSE(whole.image.pixels.empty());
      EXPECT_TRUE(split.image.pixels == whole.image.pixels);
    }
  }
  // Control: the comparison sees a slightly different shadow as a different image.
  const RenderResult a = runRender(sbtest::smallRender("gl", kScene, "exact:size=64", "none", 24));
  const RenderResult b =
      runRender(sbtest::smallRender("gl", kScene, "exact:size=64,bias=0.05", "none", 24));
  EXPECT_FALSE(a.image.pixels == b.image.pixels);
}

// More pages than are bound, or peeling (its layers are stored through one binding) over one
// page: refused before any frame, naming the pool and what to do.
TEST(ExactPaging, APoolOverThePagesBoundIsRefused) {
  auto refusal = [](const std::string& shadow) {
    try {
      runRender(sbtest::smallRender("vulkan", kScene, shadow, "none", 24));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("ran");
  };
  {
    PageBytes hook(8);  // one node a page
    const std::string e = refusal("exact:size=64");
    EXPECT_NE(e.find("exact: the node pool"), std::string::npos) << e;
    EXPECT_NE(e.find("storage bindings of at most 8 bytes on this device; 3 are bound"),
              std::string::npos)
        << e;
  }
  {
    PageBytes hook(64);
    const std::string e = refusal("exact:size=64,method=peel");
    EXPECT_NE(e.find("1 is bound: use method=abuffer"), std::string::npos) << e;
  }
  // Control: unsplit, peeling runs.
  EXPECT_EQ(refusal("exact:size=64,method=peel"), "ran");
}

}  // namespace
}  // namespace sb
