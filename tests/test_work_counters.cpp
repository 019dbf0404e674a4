// Work counters per pass (PassWork): exact, so a case repeats them run to run and
// the two APIs give the same ones; and they follow the techniques' arithmetic
// (more OSM maps, more map passes; more DOM layers, more targets written).
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "backends/device.h"
#include "harness/render.h"
#include "render_request.h"

namespace sb {
namespace {

RenderRequest small(const std::string& backend, const std::string& shadow,
                    const std::string& oit = "none") {
  return sbtest::smallRender(backend, "straight:strands=200,points=8,head=1,alpha=0.5", shadow, oit,
                             64, 2);
}

const PassWork& workOf(const RenderResult& r, const std::string& pass) {
  auto it = std::find_if(r.passes.begin(), r.passes.end(),
                         [&](const PassTimes& p) { return p.name == pass; });
  if (it == r.passes.end()) throw std::runtime_error("no pass " + pass);
  return it->work;
}

class WorkCounters : public ::testing::TestWithParam<std::string> {};

// passes=single draws one pass per map (the maps one after another), so twice
// the maps are twice the map passes' vertices and fragments.
TEST_P(WorkCounters, OsmMapFragmentsDoubleFromFourToEightMaps) {
  const RenderResult four = runRender(small(GetParam(), "osm:maps=4,passes=single,size=64"));
  const RenderResult eight = runRender(small(GetParam(), "osm:maps=8,passes=single,size=64"));
  const PassWork& a = workOf(four, "osm.map");
  const PassWork& b = workOf(eight, "osm.map");
  ASSERT_TRUE(a.statistics) << four.device.counters;
  ASSERT_GT(a.fragmentInvocations, 0u);
  EXPECT_EQ(b.fragmentInvocations, 2 * a.fragmentInvocations);
  EXPECT_EQ(b.vertices, 2 * a.vertices);
  EXPECT_EQ(b.draws, 2 * a.draws);
  EXPECT_TRUE(four.workVaries.empty());
}

// DOM stores K layers' K + 1 boundaries 4 to an RGBA32F target: 3 layers fill
// one 64x64 target (64 KiB), 4 layers need two.
TEST_P(WorkCounters, DomOpacityBytesDoubleFromThreeToFourLayers) {
  const RenderResult three = runRender(small(GetParam(), "dom:layers=3,size=64"));
  const RenderResult four = runRender(small(GetParam(), "dom:layers=4,size=64"));
  const uint64_t target = 64 * 64 * 16;
  EXPECT_EQ(workOf(three, "dom.opacity").bytesWritten, 1 * target);
  EXPECT_EQ(workOf(four, "dom.opacity").bytesWritten, 2 * target);
  // The fragments do not change: one opacity pass draws the hair once.
  EXPECT_EQ(workOf(four, "dom.opacity").fragmentInvocations,
            workOf(three, "dom.opacity").fragmentInvocations);
}

INSTANTIATE_TEST_SUITE_P(Backends, WorkCounters, ::testing::Values("gl", "vulkan"),
                         [](const auto& param) { return param.param; });

// Each case twice on each API: identical counters run to run, and GL's equal
// Vulkan's (lines, ribbons, multisampling, compute passes). Both rasterize lines
// as Bresenham/diamond-exit lines (DeviceInfo::lines), so even line fragments agree.
TEST(WorkCountersAgree, RunToRunAndAcrossApis) {
  struct Case {
    std::string shadow, oit, primitive;
    int msaa;
  };
  const Case cases[] = {{"dom:layers=3,size=64", "none", "lines", 1},
                        {"shadowmap:size=64", "wboit", "ribbons", 1},
                        {"none", "wavg", "lines", 4},
                        {"none", "abuffer", "lines", 1}};
  for (const Case& c : cases) {
    std::vector<RenderResult> runs;
    for (const char* backend : {"gl", "vulkan", "gl", "vulkan"}) {
      RenderRequest req = small(backend, c.shadow, c.oit);
      req.primitive = c.primitive;
      req.msaa = c.msaa;
      runs.push_back(runRender(req));
    }
    const std::string what = c.shadow + " " + c.oit + " " + c.primitive;
    ASSERT_EQ(runs[0].passes.size(), runs[1].passes.size()) << what;
    for (std::size_t i = 0; i < runs[0].passes.size(); ++i) {
      const std::string pass = what + " pass " + runs[0].passes[i].name;
      EXPECT_EQ(runs[0].passes[i].work, runs[2].passes[i].work) << pass << " gl run to run";
      EXPECT_EQ(runs[1].passes[i].work, runs[3].passes[i].work) << pass << " vulkan run to run";
      EXPECT_EQ(runs[0].passes[i].name, runs[1].passes[i].name) << pass;
      EXPECT_EQ(runs[0].passes[i].work, runs[1].passes[i].work) << pass << " gl against vulkan";
    }
  }
}

}  // namespace
}  // namespace sb
