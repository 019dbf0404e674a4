// Strand files as people have them, end to end through `strandbench render` and `list`:
// vertex-only PLYs (points_per_strand=), PLY meshes, text TressFX, and TressFX files cut
// inside a block the loader does not read (reported under "warnings"). The files are
// written by the tests themselves.
#include <gtest/gtest.h>

#include <cstring>
#include <nlohmann/json.hpp>

#include "test_util.h"

using sbtest::runCli;
using sbtest::tempDir;

namespace {

std::string write(const std::filesystem::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
  return p.string();
}

// NeuralHaircut-style: binary little-endian PLY, vertex x y z + uchar rgba, no strand element.
std::string vertexOnlyPly(uint32_t strands, uint32_t perStrand) {
  const uint32_t n = strands * perStrand;
  std::string b = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(n) +
                  "\nproperty float x\nproperty float y\nproperty float z\n"
                  "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                  "property uchar alpha\nend_header\n";
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t s = i / perStrand, k = i % perStrand;
    const float xyz[3] = {0.2f * float(s), -0.1f * float(k), 0.05f * float(k % 3)};
    char bytes[12];
    std::memcpy(bytes, xyz, 12);
    b.append(bytes, 12);
    const char rgba[4] = {char(200), char(40 * (s % 5)), char(30), char(255)};
    b.append(rgba, 4);
  }
  return b;
}

nlohmann::json renderJson(const std::string& scene, const std::string& backend,
                          const std::filesystem::path& out) {
  auto r = runCli("render --scene '" + scene + "' --backend " + backend +
                  " --size 48x48 --repeat 1 --json --out " + out.string());
  EXPECT_EQ(r.status, 0) << r.err;
  if (r.status != 0) return {};
  return nlohmann::json::parse(r.out);
}

TEST(RealFilesCli, PointsPerStrandGivesTheSameCountsOnGlAndVulkan) {
  const auto dir = tempDir("pps-cli");
  const std::string path = write(dir / "neural.ply", vertexOnlyPly(7, 12));
  const std::string scene = "file:path=" + path + ",points_per_strand=12";
  const nlohmann::json gl = renderJson(scene, "gl", dir / "gl.png");
  const nlohmann::json vk = renderJson(scene, "vulkan", dir / "vk.png");
  ASSERT_FALSE(gl.is_null());
  ASSERT_FALSE(vk.is_null());
  EXPECT_EQ(gl["scene"]["strands"], 7);
  EXPECT_EQ(gl["scene"]["points"], 84);
  EXPECT_EQ(gl["scene"]["segments"], 77);
  for (const char* key : {"strands", "points", "segments"}) {
    EXPECT_EQ(gl["scene"][key], vk["scene"][key]) << key;
  }
  EXPECT_TRUE(std::filesystem::exists(dir / "gl.png"));
  EXPECT_TRUE(std::filesystem::exists(dir / "vk.png"));
  std::filesystem::remove_all(dir);
}

TEST(RealFilesCli, FilesThatAreNotStrandsSayWhatToGive) {
  const auto dir = tempDir("notstrands");
  const std::string neural = write(dir / "neural.ply", vertexOnlyPly(3, 5));  // 15 vertices
  const std::string mesh = write(dir / "mesh.ply",
                                 "ply\nformat ascii 1.0\nelement vertex 3\n"
                                 "property float x\nproperty float y\nproperty float z\n"
                                 "element face 1\nproperty list uchar int vertex_indices\n"
                                 "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  struct Case {
    std::string scene;
    std::vector<std::string> needles;
  };
  const std::vector<Case> cases = {
      {"file:path=" + neural, {"neural.ply", "points_per_strand="}},
      {"file:path=" + neural + ",points_per_strand=4", {"neural.ply", "15", "points_per_strand=4"}},
      {"file:path=" + mesh, {"mesh.ply", "mesh", "mesh="}},
  };
  for (const Case& c : cases) {
    auto r = runCli("render --scene '" + c.scene + "' --out " + (dir / "o.png").string());
    EXPECT_EQ(r.status, 2) << c.scene << ": " << r.err;
    for (const std::string& n : c.needles) {
      EXPECT_NE(r.err.find(n), std::string::npos) << c.scene << ": " << r.err << "\nlacks " << n;
    }
    EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
  }
  std::filesystem::remove_all(dir);
}

// mesh= takes TressFX's .tfxmesh (the mesh beside a .tfx) and PLY meshes as well as
// OBJ; another format is named, not read as an OBJ without vertices.
TEST(RealFilesCli, MeshOptionTakesTfxMeshAndPly) {
  const auto dir = tempDir("meshes");
  const std::string data = std::string(SB_SOURCE_DIR) + "/tests/data/meshes/";
  for (const char* mesh : {"quad.tfxmesh", "quad.ply"}) {
    const nlohmann::json j =
        renderJson("straight:strands=20,points=4,mesh=" + data + mesh, "gl", dir / "o.png");
    ASSERT_FALSE(j.is_null()) << mesh;
    EXPECT_TRUE(std::filesystem::exists(dir / "o.png")) << mesh;
    std::filesystem::remove(dir / "o.png");
  }
  const std::string stl = write(dir / "part.stl", "solid part\nendsolid part\n");
  const auto r = runCli("render --scene 'straight:strands=20,mesh=" + stl + "' --out " +
                        (dir / "o.png").string());
  EXPECT_EQ(r.status, 2) << r.err;
  for (const char* n : {"part.stl", "OBJ (.obj), PLY (.ply) and TressFX (.tfxmesh)"})
    EXPECT_NE(r.err.find(n), std::string::npos) << r.err << "\nlacks " << n;
  EXPECT_EQ(r.err.find("OBJ has no vertices"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "o.png"));
  std::filesystem::remove_all(dir);
}

// The TressFX body mesh shipped beside Ratboy_mohawk.tfx, with its strands.
TEST(RealFilesCli, RatboyWithItsBodyMesh) {
  const std::string models = std::string(SB_SOURCE_DIR) + "/../shared/models/";
  if (!std::filesystem::exists(models + "Ratboy_body.tfxmesh"))
    GTEST_SKIP() << "../shared/models not found: " << models << "Ratboy_body.tfxmesh is missing";
  const auto dir = tempDir("ratboy");
  const nlohmann::json j =
      renderJson("file:path=" + models + "Ratboy_mohawk.tfx,strands=200,mesh=" + models +
                     "Ratboy_body.tfxmesh",
                 "gl", dir / "o.png");
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["scene"]["strands"], 200);
  std::filesystem::remove_all(dir);
}

TEST(RealFilesCli, TextTressFxRenders) {
  const auto dir = tempDir("tfxtext");
  std::string t =
      "version 2.0\nscale 1.0\nrotation 0 0 0\ntranslation 0 0 0\nbothEndsImmovable 0\n"
      "maxNumVerticesInStrand 4\nnumFollowHairsPerGuideHair 0\nmaxRadiusAroundGuideHair 0.1\n"
      "numStrands 3\nis sorted 1\n";
  for (int s = 0; s < 3; ++s) {
    t += "strand " + std::to_string(s) + " numVerts 4 texcoord 0.000000 0.000000\n";
    for (int v = 0; v < 4; ++v)
      t += std::to_string(0.1 * s) + " " + std::to_string(-0.2 * v) + " 0\n";
  }
  const std::string path = write(dir / "guides.tfx", t);
  const nlohmann::json j = renderJson("file:path=" + path, "gl", dir / "o.png");
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["scene"]["strands"], 3);
  EXPECT_EQ(j["scene"]["points"], 12);
  std::filesystem::remove_all(dir);
}

TEST(RealFilesCli, TressFxCutInsideAnUnreadBlockIsAWarning) {
  const auto dir = tempDir("tfxcut");
  // Version 4: 160-byte header, 2 strands x 4 float4 positions, then strand UVs cut short.
  const uint32_t strands = 2, perStrand = 4, posOffset = 160;
  const uint32_t uvOffset = posOffset + strands * perStrand * 16;
  std::string b(160, '\0');
  const float version = 4.0f;
  std::memcpy(&b[0], &version, 4);
  std::memcpy(&b[4], &strands, 4);
  std::memcpy(&b[8], &perStrand, 4);
  std::memcpy(&b[12], &posOffset, 4);
  std::memcpy(&b[16], &uvOffset, 4);
  for (uint32_t i = 0; i < strands * perStrand; ++i) {
    const float p[4] = {0.3f * float(i / perStrand), -0.2f * float(i % perStrand), 0.0f, 1.0f};
    b.append(reinterpret_cast<const char*>(p), 16);
  }
  b.append(8, '\0');  // one of the two strands' UVs
  const std::string path = write(dir / "cut.tfx", b);
  const nlohmann::json j = renderJson("file:path=" + path, "gl", dir / "o.png");
  ASSERT_FALSE(j.is_null());
  EXPECT_EQ(j["scene"]["strands"], 2);
  bool found = false;
  for (const auto& w : j["warnings"]) {
    const std::string s = w.get<std::string>();
    found |= s.find("cut.tfx") != std::string::npos && s.find("strand UV") != std::string::npos;
  }
  EXPECT_TRUE(found) << j["warnings"].dump();
  // Without --json the warning is printed too.
  auto r = runCli("render --scene file:path=" + path + " --size 16x16 --repeat 1");
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("warning: " + path), std::string::npos) << r.out;
  std::filesystem::remove_all(dir);
}

TEST(RealFilesCli, ListShowsPointsPerStrand) {
  auto r = runCli("list");
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("points_per_strand"), std::string::npos);
}

}  // namespace
