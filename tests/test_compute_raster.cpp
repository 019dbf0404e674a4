// --oit compute_raster: the compute strand rasterizer. It renders the same
// image on GL and Vulkan; with binary coverage and per-fragment shading it
// draws the hardware's own fragments, so it matches the exact reference; a
// tile list too small drops fragments that are counted in the JSON and warned
// about on stderr; it draws the strands the scene's level of detail kept; its memory is
// what the scene and options ask for.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_util.h"

namespace {

using namespace sbtest;
using json = nlohmann::json;
namespace fs = std::filesystem;

// A small groom over the head (the opaque mesh: the raster tests its depth).
const std::string kScene = "--scene curly:strands=200,points=32,seed=7,alpha=0.4 --size 64x64";

struct Result {
  json out;
  std::string err;
};

Result render(const std::string& args) {
  const CliResult r = runCli("render " + kScene + " --warmup 0 --json " + args);
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  Result run;
  if (r.status == 0) run.out = json::parse(r.out.substr(r.out.find('{')));
  run.err = r.err;
  return run;
}

double counter(const Result& r, const std::string& name) {
  return r.out["counters"].value(name, -1.0);
}

json compare(const fs::path& a, const fs::path& b) {
  const CliResult r = runCli("compare " + a.string() + " " + b.string());
  return json::parse(r.out.substr(r.out.find('{')));
}

TEST(ComputeRaster, RendersTheSameOnBothApis) {
  const fs::path dir = tempDir("craster");
  for (const std::string oit : {"compute_raster", "compute_raster:shading=fragment,tile=16"}) {
    SCOPED_TRACE(oit);
    std::map<std::string, Result> runs;
    for (const std::string backend : {"gl", "vulkan"})
      runs[backend] = render("--shadow dom:layers=3,size=128 --oit " + oit + " --backend " +
                             backend + " --out " + (dir / (backend + ".png")).string());
    const json d = compare(dir / "gl.png", dir / "vulkan.png");
    EXPECT_LE(d["max_abs"].get<double>(), 2e-3) << d.dump();
    EXPECT_GT(counter(runs["gl"], "fragments"), 1000);
    EXPECT_EQ(counter(runs["gl"], "fragments"), counter(runs["vulkan"], "fragments"));
    EXPECT_EQ(counter(runs["gl"], "dropped_fragments"), 0);
  }
  fs::remove_all(dir);
}

TEST(ComputeRaster, ThicknessWidthCoversASliverOnBothApis) {
  // width_from=thickness: the scene's 0.005-unit strands projected (a fraction of a pixel
  // here), so the hair covers less than the 1-pixel lines: fewer fragments with coverage.
  const fs::path dir = tempDir("craster-thick");
  std::map<std::string, Result> runs;
  for (const std::string backend : {"gl", "vulkan"})
    runs[backend] = render("--oit compute_raster:width_from=thickness --backend " + backend +
                           " --out " + (dir / (backend + ".png")).string());
  // The projected width is computed on each API in its own float arithmetic: one 8-bit level.
  EXPECT_LE(compare(dir / "gl.png", dir / "vulkan.png")["max_abs"].get<double>(), 5e-3);
  const Result frame = render("--oit compute_raster");
  EXPECT_GT(counter(runs["gl"], "fragments"), 100);
  EXPECT_LT(counter(runs["gl"], "fragments"), counter(frame, "fragments"));
  fs::remove_all(dir);
}

TEST(ComputeRaster, BinaryCoverageDrawsTheHardwaresFragments) {
  // coverage=binary draws the pixel centres the hardware's lines draw (up to
  // the diamond-exit rule at segment ends, a column), shaded per fragment and
  // composited without early termination: next to the exact transparency of
  // the same fragments. Exact shadows on both sides, so that the error is the
  // transparency's alone. Measured: rmse 0.0163 (binary) and 0.0192 (analytic,
  // which spreads each strand over the pixels it crosses, unlike the
  // point-sampled reference); wboit 0.0052, peel:layers=2 0.0144.
  for (const std::string backend : {"gl", "vulkan"}) {
    SCOPED_TRACE(backend);
    const Result r = render(
        "--shadow exact --oit compute_raster:coverage=binary,shading=fragment,terminate=0 "
        "--reference --backend " +
        backend);
    EXPECT_LT(r.out["error"]["image"]["rmse"].get<double>(), 0.022) << r.out["error"].dump();
    const Result a = render("--shadow exact --oit compute_raster --reference --backend " + backend);
    EXPECT_LT(a.out["error"]["image"]["rmse"].get<double>(), 0.026) << a.out["error"].dump();
  }
  // Long segments (few ends): the same image as the A-buffer's lists, same shading.
  const fs::path dir = tempDir("craster-binary");
  const std::string straight =
      "render --scene straight:strands=100,points=8,seed=3,alpha=0.4,head=0 --size 96x96 "
      "--warmup 0 --oit ";
  EXPECT_EQ(runCli(straight + "compute_raster:coverage=binary,shading=fragment,terminate=0 --out " +
                   (dir / "cr.png").string())
                .status,
            0);
  EXPECT_EQ(runCli(straight + "abuffer --out " + (dir / "ab.png").string()).status, 0);
  EXPECT_LT(compare(dir / "cr.png", dir / "ab.png")["rmse"].get<double>(), 0.009);  // 0.0064
  fs::remove_all(dir);
}

TEST(ComputeRaster, TileOverflowIsCountedAndWarned) {
  // 4 entries per 8x8 tile: the dense tiles overflow.
  const Result r = render("--oit compute_raster:fragments=4");
  EXPECT_GT(counter(r, "dropped_fragments"), 0);
  EXPECT_GT(counter(r, "overflowed_tiles"), 0);
  EXPECT_GT(counter(r, "max_tile_fragments"), 4);
  EXPECT_EQ(counter(r, "pool_fragments"), 4 * counter(r, "tiles"));
  EXPECT_NE(r.err.find("tile list overflow"), std::string::npos) << r.err;
  bool warned = false;
  for (const auto& w : r.out["warnings"])
    warned |= w.get<std::string>().find("overflow") != std::string::npos;
  EXPECT_TRUE(warned) << r.out["warnings"].dump();
  // Counted lists (the default) hold every fragment: nothing dropped, no warning.
  const Result c = render("--oit compute_raster");
  EXPECT_EQ(counter(c, "dropped_fragments"), 0);
  EXPECT_EQ(counter(c, "overflowed_tiles"), 0);
  EXPECT_EQ(counter(c, "pool_fragments"), counter(c, "fragments"));
  EXPECT_EQ(c.err.find("overflow"), std::string::npos) << c.err;
}

// Level of detail is the scene's (lod=, docs/geometry.md), one mechanism for every
// technique and geometry path: compute_raster draws the strands it kept, and with
// width_from=thickness their widened widths, so the image stays close. Its own
// lod= option is gone: refused, not ignored.
TEST(ComputeRaster, DrawsTheStrandsTheScenesLevelOfDetailKept) {
  const fs::path dir = tempDir("craster-lod");
  auto run = [&](const std::string& lod, const std::string& out) {
    const CliResult r =
        runCli("render --scene curly:strands=200,points=32,seed=7,alpha=0.4" + lod +
               " --size 64x64 --warmup 0 --json --oit compute_raster:width_from=thickness --out " +
               (dir / out).string());
    EXPECT_EQ(r.status, 0) << r.err;
    return Result{json::parse(r.out.substr(r.out.find('{'))), r.err};
  };
  const Result all = run("", "all.png"), half = run(",lod=0.5", "half.png");
  EXPECT_EQ(half.out["lod"]["strands"], 100);
  EXPECT_EQ(counter(half, "segments_drawn"), 0.5 * counter(all, "segments_drawn"));
  EXPECT_LT(compare(dir / "all.png", dir / "half.png")["rmse"].get<double>(), 0.05);
  EXPECT_EQ(runCli("render " + kScene + " --oit compute_raster:lod=0.5").status, 2);
  fs::remove_all(dir);
}

TEST(ComputeRaster, MemoryIsSizedFromTheSceneAndOptions) {
  auto bytes = [](const Result& r, const std::string& name) -> double {
    for (const auto& res : r.out["memory"]["resources"])
      if (res["name"] == name) return res["bytes"].get<double>();
    return -1;
  };
  // Counted: exactly the fragments found, 16 bytes each.
  const Result c = render("--oit compute_raster");
  EXPECT_EQ(bytes(c, "compute_raster.fragments"), 16 * counter(c, "pool_fragments"));
  // Fixed: tiles x fragments entries; no shaded ends with per-fragment shading.
  const Result f = render("--oit compute_raster:fragments=64,shading=fragment,tile=16");
  EXPECT_EQ(counter(f, "tiles"), 16);
  EXPECT_EQ(bytes(f, "compute_raster.fragments"), 16.0 * 16 * 64);
  EXPECT_EQ(bytes(f, "compute_raster.shaded"), -1);
}

}  // namespace
