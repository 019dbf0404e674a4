// The measures as units (harness/measures/measure_unit.h): each folder registers the measure
// of its name, each measure writes its own keys of the report, and the core writes none of
// them.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "harness/measures/measure_unit.h"
#include "harness/measures/own/own.h"
#include "harness/measures/probe/probe.h"
#include "harness/render.h"

namespace {

namespace fs = std::filesystem;

TEST(MeasureUnits, EachFolderRegistersTheMeasureOfItsName) {
  std::set<std::string> folders, names;
  for (const auto& e : fs::directory_iterator(fs::path(SB_SOURCE_DIR) / "harness" / "measures"))
    if (e.is_directory()) folders.insert(e.path().filename().string());
  const auto catalog = sb::measureCatalog();
  for (const sb::MeasureDescriptor* d : catalog) {
    EXPECT_EQ(d->folder, d->name);
    EXPECT_FALSE(d->help.empty()) << d->name;
    names.insert(d->name);
  }
  EXPECT_EQ(names, folders);
  // The invariants check every error the others reported: they run last.
  ASSERT_FALSE(catalog.empty());
  EXPECT_EQ(catalog.back()->name, "invariants");
}

// One small render with a reference, a probe and the invariants: each measure's keys are
// there, written by its slice; without the slices (the control) the core writes none of them.
TEST(MeasureUnits, EachSliceWritesItsOwnKeys) {
  sb::RenderRequest r;
  r.scene = "straight:strands=40,points=6";
  r.shadow = "osm:maps=4,size=64";
  r.width = r.height = 32;
  r.warmup = 0;
  r.reference = r.invariants = true;
  r.probe = sb::ProbeSpec{{32, 32}, 64, 16};
  sb::RenderResult out = sb::runRender(r);
  ASSERT_TRUE(out.measure<sb::ProbeResult>());
  EXPECT_EQ(out.measure<sb::ProbeResult>()->exact.size(), 16u);
  ASSERT_TRUE(out.measure<sb::OwnError>());
  EXPECT_EQ(out.measure<sb::OwnError>()->technique, "shadow");
  const nlohmann::json j = sb::renderJson(out);
  for (const char* key : {"probe", "invariants"}) EXPECT_TRUE(j.contains(key)) << key;
  for (const char* key : {"own", "by_eye_layers"}) EXPECT_TRUE(j["error"].contains(key)) << key;
  EXPECT_FALSE(j.contains("animation"));  // not asked for: no slice, no key
  EXPECT_FALSE(j.contains("lights"));

  out.measured.clear();
  const nlohmann::json core = sb::renderJson(out);
  for (const char* key : {"probe", "invariants"}) EXPECT_FALSE(core.contains(key)) << key;
  for (const char* key : {"own", "by_eye_layers"}) EXPECT_FALSE(core["error"].contains(key)) << key;
  EXPECT_TRUE(core["error"].contains("image"));  // the core's own error stays
}

// A further reference renders on a GL device of its own, made and gone in the middle of the
// run: the run's device must work after it (its context current again). Before, the probe
// read after it came back all zeros.
TEST(MeasureUnits, TheRunsDeviceWorksAfterAFurtherReferencesDevice) {
  for (const char* platform : {"egl", "osmesa"}) {
    sb::RenderRequest r;
    r.platform = platform;
    r.scene = "straight:strands=40,points=6";
    r.shadow = "osm:maps=4,size=64";
    r.width = r.height = 32;
    r.warmup = 0;
    r.reference = true;
    r.probe = sb::ProbeSpec{{32, 32}, 64, 16};
    const sb::RenderResult alone = sb::runRender(r);
    r.references = {"aa:samples=2"};
    const sb::RenderResult after = sb::runRender(r);
    const sb::ProbeResult* a = alone.measure<sb::ProbeResult>();
    const sb::ProbeResult* b = after.measure<sb::ProbeResult>();
    ASSERT_TRUE(a && b) << platform;
    EXPECT_EQ(a->visibility, b->visibility) << platform;
    EXPECT_EQ(a->exact, b->exact) << platform;
    // The control: the probe sees light somewhere (all zeros was the failure).
    EXPECT_GT(*std::max_element(b->visibility.begin(), b->visibility.end()), 0.0f) << platform;
  }
}

}  // namespace
