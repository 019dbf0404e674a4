// render --geometry mesh (docs/geometry.md): strands made from the groom in mesh
// shaders as they are drawn. Refused up front where it cannot run (GL, Vulkan
// without VK_EXT_mesh_shader, a scene without a groom, techniques that read the
// strands' buffers outside the strand draw). On Mesa 25.0.7's lavapipe
// (drivers/mesa-25.0, through the CLI: one process, one driver) the techniques that
// run there draw the CPU path's image, with and without a level of detail, and the
// device's strand data of a crowd is the groom alone. Each comparison also shows it
// can fail.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "base/errors.h"
#include "harness/checks.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "render/common/unit.h"
#include "tests/gpu_test_util.h"

namespace {

namespace fs = std::filesystem;

// A small groom: 2 instances of 4-strand guides (every strand of an instance its own).
constexpr const char* kGroom =
    "curly:strands=40,points=8,head=0,alpha=0.5,guides=4,clump=0.3,instances=2";

sb::RenderRequest request(const std::string& backend, const std::string& shadow,
                          const std::string& oit) {
  sb::RenderRequest r;
  r.backend = backend;
  r.scene = kGroom;
  r.shadow = shadow;
  r.oit = oit;
  r.geometry = "mesh";
  r.width = r.height = 32;
  return r;
}

std::string refusal(const sb::RenderRequest& r) {
  try {
    sb::checkRenderRequest(r, false);
  } catch (const sb::InputError& e) {
    return e.what();
  }
  return "";
}

// The shadow and transparency specs the quick suite runs: its groups' axes and the
// techniques' own quick cases (techniques/*/cases.json).
std::pair<std::set<std::string>, std::set<std::string>> quickSpecs() {
  std::set<std::string> shadows, oits;
  const auto collect = [&](const nlohmann::json& groups) {
    for (const auto& g : groups) {
      if (!g.contains("axes")) continue;
      for (const char* key : {"shadow", "oit"})
        if (g["axes"].contains(key))
          for (const auto& v : g["axes"][key])
            (std::string(key) == "shadow" ? shadows : oits).insert(v.get<std::string>());
    }
  };
  const fs::path root = SB_SOURCE_DIR;
  collect(nlohmann::json::parse(sbtest::readFile(root / "suites/quick.json"))["groups"]);
  for (const auto& e : fs::directory_iterator(root / "techniques")) {
    const fs::path cases = e.path() / "cases.json";
    if (!fs::exists(cases)) continue;
    const auto j = nlohmann::json::parse(sbtest::readFile(cases));
    if (j.contains("quick")) collect(j["quick"]);
  }
  return {shadows, oits};
}

const sb::TechniqueDescriptor& descriptor(sb::Family f, const std::string& spec) {
  return sb::findTechnique(f, sb::Spec::parse(spec).name);
}

sbtest::CliRender renderOn(const std::string& driver, const std::string& geometry,
                           const std::string& shadow, const std::string& oit,
                           const std::string& scene = kGroom, const std::string& more = "") {
  return sbtest::renderCli("--driver " + driver + " --backend vulkan --geometry " + geometry +
                           " --scene " + scene + " --shadow " + shadow + " --oit " + oit +
                           " --size 24x24 --repeat 1 --warmup 0 " + more);
}

// GL, a groomless scene and the techniques that read the strands outside the strand draw
// are refused before any device is made, each with its reason; the control passes.
TEST(GeometryMesh, RefusedUpFrontWithTheReason) {
  std::string why = refusal(request("gl", "shadowmap", "none"));
  EXPECT_NE(why.find("Vulkan only"), std::string::npos) << why;
  sb::RenderRequest r = request("vulkan", "shadowmap", "none");
  r.scene = "curly:strands=40,points=8,head=0";
  why = refusal(r);
  EXPECT_NE(why.find("groom"), std::string::npos) << why;
  for (const auto& [shadow, oit] :
       std::vector<std::pair<std::string, std::string>>{{"rt", "none"},
                                                        {"adsm", "none"},
                                                        {"none", "compute_raster"},
                                                        {"none", "rt"},
                                                        {"none", "fake"}}) {
    why = refusal(request("vulkan", shadow, oit));
    EXPECT_NE(why.find("does not run on it"), std::string::npos) << shadow << " " << oit << why;
    EXPECT_NE(why.find("--geometry compute"), std::string::npos) << why;
  }
  EXPECT_EQ(refusal(request("vulkan", "shadowmap", "abuffer")), "");  // the control
  // The command line: exit status 2, the reason, no image.
  const sbtest::CliRender gl =
      sbtest::renderCli(std::string("--backend gl --geometry mesh --size 16x16 --scene ") + kGroom);
  EXPECT_EQ(gl.status, 2) << gl.err;
  EXPECT_NE(gl.err.find("Vulkan only"), std::string::npos) << gl.err;
  EXPECT_FALSE(gl.wrote);
}

// A Vulkan driver without VK_EXT_mesh_shader (the system's lavapipe, Mesa 22.3.6)
// is refused once its device is made, naming what it lacks.
TEST(GeometryMesh, VulkanWithoutTheExtensionIsRefused) {
  std::string lacks;
  try {
    lacks = sbtest::makeDevice("vulkan")->meshPipelineRefusal();
  } catch (const sb::DeviceError& e) {
    GTEST_SKIP() << "no Vulkan device: " << e.what();
  }
  if (lacks.empty()) GTEST_SKIP() << "this system's Vulkan driver has mesh shaders";
  const sbtest::CliRender r = renderOn("system", "mesh", "shadowmap", "none");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("lacks VK_EXT_mesh_shader"), std::string::npos) << r.err;
  EXPECT_FALSE(r.wrote);
}

// Every quick-suite technique either runs on the mesh path or is refused up front with its
// reason (no device: the checks before any work).
TEST(GeometryMesh, QuickTechniquesRunOrAreRefusedUpFront) {
  const auto [shadowSpecs, oitSpecs] = quickSpecs();
  std::size_t runs[2] = {0, 0};  // shadows, transparency: those that run on the mesh path
  int refused = 0;
  for (const auto& [family, specs, count] :
       {std::tuple{sb::Family::Shadow, &shadowSpecs, &runs[0]},
        std::tuple{sb::Family::Transparency, &oitSpecs, &runs[1]}})
    for (const std::string& spec : *specs) {
      const bool shadow = family == sb::Family::Shadow;
      const std::string why =
          refusal(request("vulkan", shadow ? spec : "none", shadow ? "none" : spec));
      if (descriptor(family, spec).caps.meshRefusal.empty()) {
        EXPECT_EQ(why, "") << spec;
        ++*count;
        continue;
      }
      EXPECT_NE(why.find("does not run on it"), std::string::npos) << spec << ": " << why;
      ++refused;
    }
  EXPECT_GT(runs[0], 8u);
  EXPECT_GT(runs[1], 8u);
  EXPECT_GE(refused, 4);
}

// The mesh path draws the CPU path's image on Mesa 25.0.7's lavapipe within 1e-4 at any pixel
// (the threshold at which check counts a pixel as failing; docs/geometry.md, "Same image"):
// the same strands and vertex code, but the driver runs a mesh shader on another path than a
// vertex shader, so the last bits differ even in the eye view alone (the compute path, whose
// arithmetic is the CPU path's, gives 0: GeometryCompute.TheImageIsTheSameAndTheJsonSaysThePath).
// One pair per kind here (ctest's time); every quick-suite pair: scripts/geometry-parity.py
// (nightly). The kinds: the eye view alone; a shadow map (the nearest depth) with fragment lists
// keyed on gl_PrimitiveID; a shadow whose layers the CPU fits to the drawn strands' depth from the
// light (dom; osm and msm in the level-of-detail test below) with blended transparency; world
// ribbons (6 vertices and 2 primitives a segment, the width from the points). Control: the
// mesh path with a level of detail (lod=0.5, half the strands) is outside 1e-4 of the full
// CPU image.
TEST(GeometryMesh, RepresentativePairsDrawTheCpuImageOnMesa25) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  sbtest::CliRender cpuFull;  // shadowmap + abuffer, for the control
  const auto both = [&](const std::string& shadow, const std::string& oit,
                        const std::string& more = "") {
    const sbtest::CliRender mesh = renderOn("mesa-25.0", "mesh", shadow, oit, kGroom, more);
    sbtest::CliRender cpu = renderOn("mesa-25.0", "cpu", shadow, oit, kGroom, more);
    EXPECT_EQ(mesh.status, 0) << mesh.err;
    EXPECT_EQ(cpu.status, 0) << cpu.err;
    if (mesh.status != 0 || cpu.status != 0) return sb::ImageError{};
    EXPECT_EQ(mesh.json["geometry"], "mesh");
    const sb::ImageError e = sb::compareImages(cpu.image, mesh.image);
    std::cout << "[ measured ] " << shadow << " + " << oit << (more.empty() ? "" : " " + more)
              << ": max " << e.maxAbs << ", RMSE " << e.rmse << "\n";
    if (shadow == "shadowmap" && more.empty()) cpuFull = std::move(cpu);
    return e;
  };
  EXPECT_LE(both("none", "none").maxAbs, 1e-4) << "the eye view alone";
  EXPECT_LE(both("shadowmap", "abuffer").maxAbs, 1e-4);
  EXPECT_LE(both("dom:layers=3", "wboit").maxAbs, 1e-4);
  EXPECT_LE(both("shadowmap", "abuffer", "--primitive world").maxAbs, 1e-4) << "world ribbons";
  // The control: the comparison sees half the groom.
  const auto half =
      renderOn("mesa-25.0", "mesh", "shadowmap", "abuffer", std::string(kGroom) + ",lod=0.5");
  ASSERT_EQ(cpuFull.status, 0);
  ASSERT_EQ(half.status, 0) << half.err;
  EXPECT_GT(sb::compareImages(cpuFull.image, half.image).maxAbs, 1e-4);
}

// The level of detail on the mesh path keeps the strands the CPU keeps, widened the same
// (groomLodCutRow, integers only; the widening from the table's per-instance shares): a fixed
// share that keeps whole rows and cuts one short (lod=0.35: 14 of 40 strands in rows of 4
// guides, the cut row's guides in the groom's guide order), and a share by size on screen per
// instance of a crowd, with world widths and depth-sliced shadows, give the CPU path's image
// and strand counts. Control: the mesh path with lod_pixels= against the CPU path's full crowd.
TEST(GeometryMesh, LevelOfDetailKeepsTheCpusStrandsOnMesa25) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  const std::string crowd = "curly:strands=40,points=8,head=0,alpha=0.5,guides=4,instances=9";
  for (const auto& [scene, shadow] : std::vector<std::pair<std::string, std::string>>{
           {std::string(kGroom) + ",lod=0.35", "osm:maps=16"},
           {crowd + ",lod_pixels=12", "msm:size=64"}}) {
    SCOPED_TRACE(scene);
    const auto mesh = renderOn("mesa-25.0", "mesh", shadow, "abuffer", scene, "--primitive world");
    const auto cpu = renderOn("mesa-25.0", "cpu", shadow, "abuffer", scene, "--primitive world");
    ASSERT_EQ(mesh.status, 0) << mesh.err;
    ASSERT_EQ(cpu.status, 0) << cpu.err;
    EXPECT_EQ(mesh.json["lod"]["strands"], cpu.json["lod"]["strands"]);
    EXPECT_LT(mesh.json["lod"]["strands"].get<double>(),
              mesh.json["lod"]["strands_full"].get<double>());
    const sb::ImageError e = sb::compareImages(cpu.image, mesh.image);
    std::cout << "[ measured ] " << scene << ", " << shadow << ": " << mesh.json["lod"]["strands"]
              << " of " << mesh.json["lod"]["strands_full"] << " strands, max " << e.maxAbs
              << ", RMSE " << e.rmse << "\n";
    EXPECT_LE(e.maxAbs, 1e-4);
  }
  const auto full =
      renderOn("mesa-25.0", "cpu", "msm:size=64", "abuffer", crowd, "--primitive world");
  const auto kept = renderOn("mesa-25.0", "mesh", "msm:size=64", "abuffer",
                             crowd + ",lod_pixels=12", "--primitive world");
  ASSERT_EQ(full.status, 0) << full.err;
  ASSERT_EQ(kept.status, 0) << kept.err;
  EXPECT_GT(sb::compareImages(full.image, kept.image).maxAbs, 1e-4);
}

// A crowd's strand data on the device (the render JSON's memory by owner, "scene"; no
// head, so the scene's buffers are strand data alone): on the mesh path only the groom,
// at most a tenth of the CPU path's. Under a memory limit between the two the CPU path
// is refused up front with the bytes it needs, and the mesh path runs (the control).
TEST(GeometryMesh, ACrowdsStrandDataIsTheGroomOnMesa25) {
  if (const std::string why = sbtest::mesa25Missing(); !why.empty()) GTEST_SKIP() << why;
  const std::string crowd = "straight:strands=400,points=16,head=0,guides=8,instances=10";
  const auto cpu = renderOn("mesa-25.0", "cpu", "shadowmap", "none", crowd);
  const auto mesh = renderOn("mesa-25.0", "mesh", "shadowmap", "none", crowd);
  ASSERT_EQ(cpu.status, 0) << cpu.err;
  ASSERT_EQ(mesh.status, 0) << mesh.err;
  const double cpuBytes = cpu.json["memory"]["scene_bytes"].get<double>();
  const double meshBytes = mesh.json["memory"]["scene_bytes"].get<double>();
  std::cout << "[ measured ] 10-instance crowd, strand data on the device: cpu " << cpuBytes
            << " bytes, mesh " << meshBytes << " bytes\n";
  // Points and colours, segments, and the three 16-byte stand-ins for the absent head.
  EXPECT_EQ(cpuBytes, 10.0 * 400 * 16 * 32 + 10.0 * 400 * 15 * 4 + 3 * 16);
  EXPECT_LE(meshBytes * 10, cpuBytes);
  // Between the two runs' totals (only their strand data differs).
  const auto total = [](const sbtest::CliRender& r) {
    return static_cast<long long>(r.json["memory"]["total_bytes"].get<double>());
  };
  const std::string limit = "--memory-limit " + std::to_string((total(cpu) + total(mesh)) / 2);
  const auto refused = renderOn("mesa-25.0", "cpu", "shadowmap", "none", crowd, limit);
  EXPECT_EQ(refused.status, 2) << refused.err;
  EXPECT_NE(refused.err.find("needs " + std::to_string(total(cpu)) + " bytes"), std::string::npos)
      << refused.err;
  EXPECT_FALSE(refused.wrote);
  const auto fits = renderOn("mesa-25.0", "mesh", "shadowmap", "none", crowd, limit);
  EXPECT_EQ(fits.status, 0) << fits.err;
}

}  // namespace
