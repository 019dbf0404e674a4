// Loader tests: the real models in ../shared/models (skipped when absent) and
// malformed inputs built in memory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "scenes/mesh_loaders.h"
#include "scenes/scene.h"
#include "test_util.h"

using sbtest::expectInputError;

namespace {

using Bytes = std::vector<uint8_t>;

std::string modelsDir() { return std::string(SB_SOURCE_DIR) + "/../shared/models"; }

#define REQUIRE_MODEL(file)                                                  \
  const std::string path = modelsDir() + "/" + (file);                       \
  if (!std::filesystem::exists(path)) {                                      \
    GTEST_SKIP() << "../shared/models not found: " << path << " is missing"; \
  }

// ---------------------------------------------------------------- real models

TEST(RealModels, StraightHair) {
  REQUIRE_MODEL("straight.hair");
  const sb::Strands s = sb::loadHair(path);
  sbtest::expectWellFormed(s);
  EXPECT_EQ(s.strandCount(), 10000u);
  EXPECT_EQ(s.points.size(), 160000u);
  EXPECT_EQ(s.segmentCount(), 150000u);
  for (uint32_t c : s.pointCount) ASSERT_EQ(c, 16u);
  EXPECT_FLOAT_EQ(s.thickness[0], 0.1f);     // header default
  EXPECT_FLOAT_EQ(s.colors.back().x, 1.0f);  // per-point colours from the file (blond)
}

TEST(RealModels, BearTfxVersion3) {
  REQUIRE_MODEL("bear.tfx");
  const sb::Strands s = sb::loadTfx(path);
  sbtest::expectWellFormed(s);
  EXPECT_EQ(s.strandCount(), 48113u);
  EXPECT_EQ(s.points.size(), 48113u * 4u);
  for (uint32_t c : s.pointCount) ASSERT_EQ(c, 4u);
}

TEST(RealModels, RatboyTfxVersion4) {
  REQUIRE_MODEL("Ratboy_mohawk.tfx");
  const sb::Strands s = sb::loadTfx(path);
  sbtest::expectWellFormed(s);
  EXPECT_EQ(s.strandCount(), 2228u);
  EXPECT_EQ(s.points.size(), 2228u * 32u);
  // float4 positions: consecutive points of a strand are close (w ignored, stride right).
  EXPECT_LT(glm::length(s.points[1] - s.points[0]), 1.0f);
}

TEST(RealModels, CurlyPly) {
  REQUIRE_MODEL("Curly_100.ply");
  const sb::Strands s = sb::loadPly(path);
  sbtest::expectWellFormed(s);
  EXPECT_EQ(s.strandCount(), 100u);
  EXPECT_EQ(s.points.size(), 2528u);
  EXPECT_EQ(s.segmentCount(), 2428u);  // matches the file's edge element
}

TEST(RealModels, StrandFileByExtension) {
  REQUIRE_MODEL("Curly_100.ply");
  EXPECT_EQ(sb::loadStrandFile(path).strandCount(), 100u);
  EXPECT_EQ(sb::loadStrandFile(modelsDir() + "/bear.tfx").strandCount(), 48113u);
  expectInputError([] { sb::loadStrandFile("x/model.abc"); }, {"model.abc", ".abc"});
}

// The counts of a real mesh, unit normals, every index in range.
void expectMesh(const sb::Mesh& m, std::size_t vertices, std::size_t triangles) {
  EXPECT_EQ(m.positions.size(), vertices);
  EXPECT_EQ(m.triangleCount(), triangles);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
  for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
}

TEST(RealModels, BunnyObj) {
  REQUIRE_MODEL("stanford-bunny.obj");
  expectMesh(sb::loadObj(path), 35947, 69451);
}

TEST(RealModels, TeapotObj) {
  REQUIRE_MODEL("teapot.obj");
  expectMesh(sb::loadObj(path), 3644, 6320);
}

// The body mesh shipped beside Ratboy_mohawk.tfx (TressFX 4's text .tfxmesh).
TEST(RealModels, RatboyBodyTfxMesh) {
  REQUIRE_MODEL("Ratboy_body.tfxmesh");
  expectMesh(sb::loadMesh(path), 12909, 25814);
  const sb::Scene scene = sb::makeScene(
      sb::Spec::parse("file:path=" + modelsDir() + "/Ratboy_mohawk.tfx,strands=100,mesh=" + path));
  EXPECT_EQ(scene.mesh.positions.size(), 12909u);
}

TEST(RealModels, FileScene) {
  REQUIRE_MODEL("straight.hair");
  const sb::Scene all = sb::makeScene(sb::Spec::parse("file:path=" + path));
  EXPECT_EQ(all.strands.strandCount(), 10000u);
  EXPECT_TRUE(all.mesh.positions.empty());
  const sb::Scene some = sb::makeScene(
      sb::Spec::parse("file:path=" + path + ",strands=2500,mesh=" + modelsDir() + "/teapot.obj"));
  sbtest::expectWellFormed(some.strands);
  EXPECT_EQ(some.strands.strandCount(), 2500u);
  EXPECT_EQ(some.strands.points.size(), 2500u * 16u);
  EXPECT_EQ(some.mesh.positions.size(), 3644u);
  expectInputError([&] { sb::makeScene(sb::Spec::parse("file:path=" + path + ",strands=20000")); },
                   {"strands=20000", "10000"});
}

TEST(Loaders, CannotOpenNamesThePath) {
  const std::string p = "/nonexistent/dir/missing.hair";
  expectInputError([&] { sb::loadHair(p); }, {p});
  expectInputError([&] { sb::loadTfx("/nonexistent/a.tfx"); }, {"/nonexistent/a.tfx"});
  expectInputError([&] { sb::loadPly("/nonexistent/a.ply"); }, {"/nonexistent/a.ply"});
  expectInputError([&] { sb::loadObj("/nonexistent/a.obj"); }, {"/nonexistent/a.obj"});
  expectInputError([] { sb::makeScene(sb::Spec::parse("file:path=/nonexistent/b.hair")); },
                   {"/nonexistent/b.hair"});
  expectInputError([] { sb::makeScene(sb::Spec::parse("file")); }, {"path="});
}

// A model whose git-lfs content was never fetched is named as such, whatever its
// format (each loader alone would call it short or malformed).
TEST(Loaders, GitLfsPointerIsNamed) {
  const auto dir = sbtest::tempDir("lfs");
  const std::string pointer =
      "version https://git-lfs.github.com/spec/v1\n"
      "oid sha256:4d7a214614ab2935c943f9e0ff69d22eadbb8f32b1258daaa5e2ca24d17e2393\n"
      "size 3840128\n";
  for (const char* name : {"m.hair", "m.tfx", "m.ply", "m.obj", "m.tfxmesh"}) {
    const std::string path = (dir / name).string();
    std::ofstream(path) << pointer;
    const std::vector<std::string> needles = {path, "unfetched git-lfs pointer", "3840128 bytes",
                                              "git lfs pull"};
    const std::string ext = std::filesystem::path(path).extension().string();
    if (ext == ".hair" || ext == ".tfx" || ext == ".ply") {  // strands
      expectInputError([&] { sb::loadStrandFile(path); }, needles);
      expectInputError([&] { sb::makeScene(sb::Spec::parse("file:path=" + path)); }, needles);
    }
    if (ext == ".obj" || ext == ".ply" || ext == ".tfxmesh")  // meshes
      expectInputError([&] { sb::makeScene(sb::Spec::parse("straight:strands=4,mesh=" + path)); },
                       needles);
  }
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------- HAIR builder

void put32(Bytes& b, std::size_t at, uint32_t v) { std::memcpy(b.data() + at, &v, 4); }
void putF(Bytes& b, std::size_t at, float v) { std::memcpy(b.data() + at, &v, 4); }
void appendF(Bytes& b, float v) {
  b.resize(b.size() + 4);
  putF(b, b.size() - 4, v);
}
void append16(Bytes& b, uint16_t v) {
  b.push_back(uint8_t(v & 0xff));
  b.push_back(uint8_t(v >> 8));
}

// Two strands: 3 points and 2 points (segments array), with every array present.
Bytes smallHair(uint32_t flags = 0x1f) {
  Bytes b(128, 0);
  std::memcpy(b.data(), "HAIR", 4);
  put32(b, 4, 2);
  put32(b, 8, 5);
  put32(b, 12, flags);
  put32(b, 16, 2);     // default segments
  putF(b, 20, 0.25f);  // default thickness
  putF(b, 24, 0.5f);   // default transparency
  putF(b, 28, 0.1f);   // default colour
  putF(b, 32, 0.2f);
  putF(b, 36, 0.3f);
  if (flags & 1) {
    append16(b, 2);
    append16(b, 1);
  }
  if (flags & 2) {
    for (int i = 0; i < 15; ++i) appendF(b, float(i));
  }
  if (flags & 4) {
    for (int i = 0; i < 5; ++i) appendF(b, 0.01f * float(i + 1));
  }
  if (flags & 8) {
    for (int i = 0; i < 5; ++i) appendF(b, 0.0f);
  }
  if (flags & 16) {
    for (int i = 0; i < 15; ++i) appendF(b, 0.5f);
  }
  return b;
}

sb::Strands hair(const Bytes& b) { return sb::parseHair(b.data(), b.size(), "mem.hair"); }

TEST(HairParser, SmallValidFile) {
  const sb::Strands s = hair(smallHair());
  sbtest::expectWellFormed(s);
  ASSERT_EQ(s.strandCount(), 2u);
  EXPECT_EQ(s.pointCount[0], 3u);
  EXPECT_EQ(s.pointCount[1], 2u);
  EXPECT_EQ(s.firstPoint[1], 3u);
  EXPECT_EQ(s.points[4], glm::vec3(12, 13, 14));
  EXPECT_FLOAT_EQ(s.thickness[4], 0.05f);
  EXPECT_EQ(s.colors[2], glm::vec3(0.5f));
}

TEST(HairParser, DefaultsForAbsentArrays) {
  // Points only, no segments array: default segments 2 -> but 5 points != 2 x 3.
  expectInputError([] { hair(smallHair(0x2)); }, {"mem.hair", "default segments"});
  Bytes b = smallHair(0x2);
  put32(b, 8, 6);  // 2 strands x 3 points
  for (int i = 0; i < 3; ++i) appendF(b, 1.0f);
  const sb::Strands s = hair(b);
  sbtest::expectWellFormed(s);
  EXPECT_EQ(s.strandCount(), 2u);
  EXPECT_EQ(s.pointCount[1], 3u);
  EXPECT_FLOAT_EQ(s.thickness[3], 0.25f);
  EXPECT_FLOAT_EQ(s.transparency[3], 0.5f);
  EXPECT_EQ(s.colors[5], glm::vec3(0.1f, 0.2f, 0.3f));
}

TEST(HairParser, EveryTruncationIsRejected) {
  const Bytes full = smallHair();
  for (std::size_t n = 0; n < full.size(); ++n) {
    const Bytes cut(full.begin(), full.begin() + std::ptrdiff_t(n));
    expectInputError([&] { hair(cut); }, {"mem.hair"});
  }
}

TEST(HairParser, Malformed) {
  Bytes b = smallHair();
  b[0] = 'X';
  expectInputError([&] { hair(b); }, {"mem.hair", "HAIR"});

  b = smallHair();
  put32(b, 4, 0);
  expectInputError([&] { hair(b); }, {"mem.hair", "zero strands"});

  b = smallHair();
  put32(b, 8, 0);
  expectInputError([&] { hair(b); }, {"mem.hair", "zero points"});

  b = smallHair();
  put32(b, 8, 1000000000);  // far more points than the file holds
  expectInputError([&] { hair(b); }, {"mem.hair", "truncated"});

  b = smallHair();
  put32(b, 4, 0xffffffffu);  // strand count larger than the file
  expectInputError([&] { hair(b); }, {"mem.hair", "truncated"});

  b = smallHair();
  b[128] = 3;  // first strand 3 segments: 6 points, header says 5
  expectInputError([&] { hair(b); }, {"mem.hair", "segments array"});

  b = smallHair();
  putF(b, 128 + 4 + 4 * 4, std::numeric_limits<float>::quiet_NaN());
  expectInputError([&] { hair(b); }, {"mem.hair", "NaN"});

  b = smallHair();
  putF(b, 128 + 4, std::numeric_limits<float>::infinity());
  expectInputError([&] { hair(b); }, {"mem.hair", "infinite"});

  expectInputError([] { hair(smallHair(0x1)); }, {"mem.hair", "points array"});

  expectInputError([] { sb::parseHair(nullptr, 0, "empty.hair"); }, {"empty.hair"});
}

// ---------------------------------------------------------------- TFX builder

Bytes smallTfx(int version, uint32_t strands = 3, uint32_t perStrand = 4) {
  const std::size_t header = version == 3 ? 296 : 160;
  Bytes b(header, 0);
  putF(b, 0, float(version));
  put32(b, 4, strands);
  put32(b, 8, perStrand);
  put32(b, 12, version == 3 ? 0 : 160);
  for (uint32_t i = 0; i < strands * perStrand; ++i) {
    appendF(b, float(i));
    appendF(b, 1.0f);
    appendF(b, -float(i));
    if (version == 4) appendF(b, 1.0f);
  }
  return b;
}

sb::Strands tfx(const Bytes& b) { return sb::parseTfx(b.data(), b.size(), "mem.tfx"); }

TEST(TfxParser, Versions3And4) {
  for (int v : {3, 4}) {
    const sb::Strands s = tfx(smallTfx(v));
    sbtest::expectWellFormed(s);
    EXPECT_EQ(s.strandCount(), 3u);
    EXPECT_EQ(s.points.size(), 12u);
    EXPECT_EQ(s.points[5], glm::vec3(5, 1, -5)) << "version " << v;
  }
}

TEST(TfxParser, Malformed) {
  Bytes b = smallTfx(4);
  putF(b, 0, 2.0f);
  expectInputError([&] { tfx(b); }, {"mem.tfx", "version"});

  b = smallTfx(4);
  putF(b, 0, std::numeric_limits<float>::quiet_NaN());
  expectInputError([&] { tfx(b); }, {"mem.tfx", "version"});

  b = smallTfx(3);
  b.resize(200);  // cut inside the 296-byte header
  expectInputError([&] { tfx(b); }, {"mem.tfx", "truncated"});

  b = smallTfx(4);
  b.pop_back();
  expectInputError([&] { tfx(b); }, {"mem.tfx", "truncated"});

  b = smallTfx(3);
  put32(b, 4, 0xffffffffu);
  put32(b, 8, 0xffffffffu);  // counts far larger than the file (and than 32 bits)
  expectInputError([&] { tfx(b); }, {"mem.tfx"});

  b = smallTfx(4);
  put32(b, 4, 0);
  expectInputError([&] { tfx(b); }, {"mem.tfx", "zero strands"});

  b = smallTfx(4);
  put32(b, 12, 0xfffffff0u);  // offset past the end
  expectInputError([&] { tfx(b); }, {"mem.tfx", "truncated"});

  b = smallTfx(4);
  put32(b, 12, 8);  // offset inside the header
  expectInputError([&] { tfx(b); }, {"mem.tfx", "header"});

  b = smallTfx(3);
  putF(b, 296 + 12 * 7 + 4, std::numeric_limits<float>::infinity());
  expectInputError([&] { tfx(b); }, {"mem.tfx", "infinite"});

  const Bytes full = smallTfx(4);
  for (std::size_t n = 0; n < full.size(); n += 7) {
    const Bytes cut(full.begin(), full.begin() + std::ptrdiff_t(n));
    expectInputError([&] { tfx(cut); }, {"mem.tfx"});
  }
}

// Version 4 with a strand UV block after the positions (as Ratboy_mohawk.tfx), optionally
// cut short by `cut` bytes.
Bytes tfxWithUvs(std::size_t cut) {
  Bytes b = smallTfx(4);             // 3 strands x 4 points
  put32(b, 16, uint32_t(b.size()));  // offsetStrandUV: right after the positions
  for (int i = 0; i < 3 * 2; ++i) appendF(b, 0.5f);
  b.resize(b.size() - cut);
  return b;
}

TEST(TfxParser, CutInsideUnreadBlockIsAcceptedWithAWarning) {
  std::vector<std::string> warnings;
  const Bytes complete = tfxWithUvs(0);
  const sb::Strands whole = sb::parseTfx(complete.data(), complete.size(), "mem.tfx", &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  EXPECT_EQ(whole.strandCount(), 3u);
  for (std::size_t cut : {std::size_t(1), std::size_t(12), std::size_t(24)}) {
    warnings.clear();
    const Bytes b = tfxWithUvs(cut);
    const sb::Strands s = sb::parseTfx(b.data(), b.size(), "mem.tfx", &warnings);
    sbtest::expectWellFormed(s);
    EXPECT_EQ(s.strandCount(), 3u);
    EXPECT_EQ(s.points, whole.points);
    ASSERT_EQ(warnings.size(), 1u) << "cut " << cut;
    for (const char* needle : {"mem.tfx", "strand UV", "truncated"}) {
      EXPECT_NE(warnings[0].find(needle), std::string::npos) << warnings[0];
    }
  }
  // Without a place for warnings the file still loads (the fuzz targets' and tests' call).
  const Bytes cut = tfxWithUvs(5);
  EXPECT_EQ(tfx(cut).strandCount(), 3u);
  // A cut inside the positions is still an error, UV block or not.
  Bytes b = tfxWithUvs(24);
  b.resize(b.size() - 1);
  expectInputError([&] { tfx(b); }, {"mem.tfx", "truncated"});
  // Every other later block is checked too: vertex colours (float4 per point) declared, absent.
  b = smallTfx(4);
  put32(b, 28, uint32_t(b.size()));
  warnings.clear();
  sb::parseTfx(b.data(), b.size(), "mem.tfx", &warnings);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("vertex colour"), std::string::npos) << warnings[0];
}

// ---------------------------------------------------------------- TFX text (1.x / 2.x)

Bytes text(const std::string& s) { return Bytes(s.begin(), s.end()); }

// Two strands (3 and 2 points) in the TressFX 2.0 sample layout.
const char* kTextTfx =
    "version 2.0\n"
    "scale 1.0\n"
    "rotation 0 0 0\n"
    "translation 0 0 0\n"
    "bothEndsImmovable 0\n"
    "maxNumVerticesInStrand 3\n"
    "numFollowHairsPerGuideHair 4\n"
    "maxRadiusAroundGuideHair 0.5\n"
    "numStrands 2\n"
    "is sorted 1\n"
    "strand 0 numVerts 3 texcoord 0.000000 0.522833\n"
    "0.0 0.0 0.0\n"
    "0.0 1.0 0.0\n"
    "0.0 2.0 0.5\n"
    "strand 1 numVerts 2 texcoord 0.100000 000000\n"
    "1.0 0.0 0.0\n"
    "1.0 -1.5 0.0\n";

std::string replaced(std::string s, const std::string& from, const std::string& to) {
  const std::size_t p = s.find(from);
  EXPECT_NE(p, std::string::npos) << from;
  if (p != std::string::npos) s.replace(p, from.size(), to);
  return s;
}

TEST(TfxTextParser, Version2) {
  const sb::Strands s = tfx(text(kTextTfx));
  sbtest::expectWellFormed(s);
  ASSERT_EQ(s.strandCount(), 2u);
  EXPECT_EQ(s.pointCount[0], 3u);
  EXPECT_EQ(s.pointCount[1], 2u);
  EXPECT_EQ(s.points[2], glm::vec3(0.0f, 2.0f, 0.5f));
  EXPECT_EQ(s.points[4], glm::vec3(1.0f, -1.5f, 0.0f));
}

TEST(TfxTextParser, Version1CommasCrLfAndBlankLines) {
  // 1.x files start at numStrands; some exporters write "x, y, z"; Windows line ends.
  std::string t =
      "numStrands 1\r\nis sorted 1\r\n\r\nstrand 0 numVerts 2 texcoord 0 0\r\n"
      "0.5, 1, 2\r\n\r\n3, 4, 5\r\n";
  const sb::Strands s = tfx(text(t));
  sbtest::expectWellFormed(s);
  ASSERT_EQ(s.strandCount(), 1u);
  EXPECT_EQ(s.points[0], glm::vec3(0.5f, 1.0f, 2.0f));
  EXPECT_EQ(s.points[1], glm::vec3(3.0f, 4.0f, 5.0f));
  // A UTF-8 byte order mark and no texcoord are fine too.
  EXPECT_EQ(tfx(text("\xEF\xBB\xBFnumStrands 1\nstrand 0 numVerts 1\n1 2 3\n")).points[0],
            glm::vec3(1, 2, 3));
}

TEST(TfxTextParser, ScaleRotationTranslationAsAmdsLoader) {
  // scale, then roll (z), pitch (x), yaw (y) in radians, then translation.
  const float half = 1.5707963267948966f;
  std::string t = replaced(kTextTfx, "scale 1.0", "scale 2.0");
  t = replaced(t, "rotation 0 0 0", "rotation 0 " + std::to_string(half) + " 0");
  t = replaced(t, "translation 0 0 0", "translation 10 20 30");
  const sb::Strands s = tfx(text(t));
  // (0, 2, 0.5) -> scaled (0, 4, 1) -> yaw 90 degrees about y: (1, 4, 0) -> + (10, 20, 30).
  EXPECT_NEAR(s.points[2].x, 11.0f, 1e-5f);
  EXPECT_NEAR(s.points[2].y, 24.0f, 1e-5f);
  EXPECT_NEAR(s.points[2].z, 30.0f, 1e-5f);
  // Roll about z: (1, 0, 0) -> (0, 1, 0).
  t = replaced(kTextTfx, "rotation 0 0 0", "rotation 0 0 " + std::to_string(half));
  const sb::Strands r = tfx(text(t));
  EXPECT_NEAR(r.points[3].x, 0.0f, 1e-5f);
  EXPECT_NEAR(r.points[3].y, 1.0f, 1e-5f);
  // Pitch about x: (0, 1, 0) -> (0, 0, 1).
  t = replaced(kTextTfx, "rotation 0 0 0", "rotation " + std::to_string(half) + " 0 0");
  const sb::Strands q = tfx(text(t));
  EXPECT_NEAR(q.points[1].y, 0.0f, 1e-5f);
  EXPECT_NEAR(q.points[1].z, 1.0f, 1e-5f);
}

TEST(TfxTextParser, EveryMalformedLineNamesFileAndLine) {
  const std::string a = kTextTfx;
  struct Case {
    std::string from, to, line, what;
  };
  const std::vector<Case> cases = {
      {"version 2.0", "version 7.5", "line 1", "7.5"},
      {"version 2.0", "version two", "line 1", "two"},
      {"scale 1.0", "scale", "line 2", "scale"},
      {"scale 1.0", "scale nan", "line 2", "nan"},
      {"rotation 0 0 0", "rotation 0 0", "line 3", "rotation"},
      {"translation 0 0 0", "translation 0 0 1e999", "line 4", "1e999"},
      {"bothEndsImmovable 0", "bothEndsImmovable x", "line 5", "'x'"},
      {"maxNumVerticesInStrand 3", "maxNumVerticesInStrand -3", "line 6", "-3"},
      {"numStrands 2", "numStrands 0", "line 9", "numStrands"},
      {"numStrands 2", "numStrands 2.5", "line 9", "2.5"},
      {"is sorted 1", "is unsorted", "line 10", "is sorted"},
      {"is sorted 1", "17 18", "line 10", "'17'"},
      {"strand 0 numVerts 3", "strand 0 numVerts x", "line 11", "'x'"},
      {"strand 0 numVerts 3", "strand 0 numVerts 0", "line 11", "numVerts"},
      {"strand 0 numVerts 3", "strand 0 nverts 3", "line 11", "numVerts"},
      {"strand 0 numVerts 3", "strand -1 numVerts 3", "line 11", "strand index"},
      {"texcoord 0.000000 0.522833", "texcoord 0.5", "line 11", "texcoord"},
      {"texcoord 0.000000 0.522833", "uv 0 0", "line 11", "texcoord"},
      {"0.0 1.0 0.0", "0.0 1.0", "line 13", "x y z"},
      {"0.0 1.0 0.0", "0.0 1.0 0.0 1.0", "line 13", "x y z"},
      {"0.0 1.0 0.0", "0.0 1,0 0.0", "line 13", "x y z"},  // decimal comma
      {"0.0 1.0 0.0", "0.0 -1.#INF 0.0", "line 13", "-1.#INF"},
      {"0.0 2.0 0.5", "strand 9 numVerts 1", "line 14", "x y z"},  // numVerts says 3
      {"strand 1 numVerts 2", "strnd 1 numVerts 2", "line 15", "strnd"},
      {"1.0 -1.5 0.0\n", "1.0 -1.5 0.0\n0 0 0\n", "line 18", "more data"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.to);
    expectInputError([&] { tfx(text(replaced(a, c.from, c.to))); }, {"mem.tfx", c.line, c.what});
  }
  // Scale times a coordinate overflows float: the vertex's line is named.
  std::string t = replaced(a, "scale 1.0", "scale 1e30");
  t = replaced(t, "0.0 1.0 0.0", "0.0 1e20 0.0");
  expectInputError([&] { tfx(text(t)); }, {"mem.tfx", "line 13", "finite"});
  // numStrands missing before the strands.
  expectInputError([&] { tfx(text(replaced(a, "numStrands 2\n", ""))); },
                   {"mem.tfx", "numStrands"});
  // Declared strands missing.
  expectInputError([&] { tfx(text(replaced(a, "numStrands 2", "numStrands 3"))); },
                   {"mem.tfx", "truncated", "3 strands"});
}

TEST(TfxTextParser, EveryCutAtALineEndIsRejected) {
  const std::string a = kTextTfx;
  for (std::size_t p = a.find('\n'); p + 1 < a.size(); p = a.find('\n', p + 1)) {
    const std::string cut = a.substr(0, p + 1);
    SCOPED_TRACE(cut);
    expectInputError([&] { tfx(text(cut)); }, {"mem.tfx"});
  }
}

TEST(TfxTextParser, OtherTextIsNotReadAsBinary) {
  // Text that is not TressFX: said plainly, not "unsupported TressFX version 1.9e31".
  expectInputError([] { tfx(text("hello, this is not hair data\n")); },
                   {"mem.tfx", "text", "version 2.0"});
  expectInputError([] { tfx(text("version 2.0\nstrand 0 numVerts 1\n1 2 3\n")); },
                   {"mem.tfx", "numStrands"});
}

// ---------------------------------------------------------------- PLY builder

sb::Strands ply(const Bytes& b) { return sb::parsePly(b.data(), b.size(), "mem.ply"); }

const char* kAsciiPly =
    "ply\n"
    "format ascii 1.0\n"
    "comment two strands\n"
    "element vertex 5\n"
    "property float x\nproperty float y\nproperty float z\n"
    "property uchar red\nproperty uchar green\nproperty uchar blue\n"
    "element strand 2\n"
    "property ushort nsegs\n"
    "element face 1\n"
    "property list uchar int vertex_indices\n"
    "end_header\n"
    "0 0 0 255 0 0\n1 0 0 255 0 0\n2 0 0 255 0 0\n"
    "0 1 0 0 0 255\n0 2 0 0 0 255\n"
    "2\n1\n"
    "3 0 1 2\n";

Bytes binaryPly(bool bigEndian, uint16_t firstSegs = 2) {
  std::string h = std::string("ply\nformat ") +
                  (bigEndian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\n"
                  "element vertex 5\n"
                  "property double x\nproperty double y\nproperty double z\n"
                  "element edge 1\nproperty list uchar int vertex_indices\n"
                  "element strand 2\nproperty int nsegs\n"
                  "end_header\n";
  Bytes b = text(h);
  auto put = [&](const void* p, std::size_t n) {
    const uint8_t* q = static_cast<const uint8_t*>(p);
    for (std::size_t i = 0; i < n; ++i) b.push_back(q[bigEndian ? n - 1 - i : i]);
  };
  for (int v = 0; v < 5; ++v) {
    for (int k = 0; k < 3; ++k) {
      const double d = v * 10 + k;
      put(&d, 8);
    }
  }
  const uint8_t n = 2;
  put(&n, 1);
  const int32_t e[2] = {0, 1};
  put(&e[0], 4);
  put(&e[1], 4);
  const int32_t segs[2] = {firstSegs, 1};
  put(&segs[0], 4);
  put(&segs[1], 4);
  return b;
}

TEST(PlyParser, AsciiWithColoursAndLists) {
  const sb::Strands s = ply(text(kAsciiPly));
  sbtest::expectWellFormed(s);
  ASSERT_EQ(s.strandCount(), 2u);
  EXPECT_EQ(s.pointCount[0], 3u);
  EXPECT_EQ(s.pointCount[1], 2u);
  EXPECT_EQ(s.points[4], glm::vec3(0, 2, 0));
  EXPECT_EQ(s.colors[0], glm::vec3(1, 0, 0));
  EXPECT_EQ(s.colors[4], glm::vec3(0, 0, 1));
}

TEST(PlyParser, BinaryBothEndians) {
  for (bool be : {false, true}) {
    const sb::Strands s = ply(binaryPly(be));
    sbtest::expectWellFormed(s);
    ASSERT_EQ(s.strandCount(), 2u) << (be ? "big" : "little");
    EXPECT_EQ(s.points[3], glm::vec3(30, 31, 32));
    EXPECT_EQ(s.pointCount[0], 3u);
  }
}

TEST(PlyParser, CrLfHeader) {
  std::string t = kAsciiPly;
  std::string crlf;
  for (char c : t) {
    if (c == '\n') crlf += '\r';
    crlf += c;
  }
  EXPECT_EQ(ply(text(crlf)).strandCount(), 2u);
}

TEST(PlyParser, BadHeaders) {
  auto replace = [](std::string s, const std::string& from, const std::string& to) {
    const std::size_t p = s.find(from);
    EXPECT_NE(p, std::string::npos) << from;
    if (p != std::string::npos) s.replace(p, from.size(), to);
    return text(s);
  };
  const std::string a = kAsciiPly;
  expectInputError([&] { ply(replace(a, "ply\n", "plx\n")); }, {"mem.ply", "not a PLY"});
  expectInputError([&] { ply(replace(a, "format ascii 1.0", "format foo 1.0")); },
                   {"mem.ply", "format"});
  expectInputError([&] { ply(replace(a, "format ascii 1.0\n", "")); }, {"mem.ply", "format"});
  expectInputError([&] { ply(replace(a, "end_header", "end_headr")); }, {"mem.ply"});
  expectInputError([&] { ply(text(a.substr(0, a.find("end_header")))); },
                   {"mem.ply", "end_header"});
  expectInputError([&] { ply(replace(a, "property float y", "property flot y")); },
                   {"mem.ply", "flot"});
  expectInputError([&] { ply(replace(a, "property float z", "property float w")); },
                   {"mem.ply", "x, y or z"});
  expectInputError([&] { ply(replace(a, "element strand 2\nproperty ushort nsegs\n", "")); },
                   {"mem.ply", "strand"});
  expectInputError([&] { ply(replace(a, "element vertex 5", "element vertex five")); },
                   {"mem.ply", "five"});
  expectInputError([&] { ply(replace(a, "property ushort nsegs", "property float nsegs")); },
                   {"mem.ply", "integer"});
  expectInputError([&] { ply(replace(a, "property uchar red", "property list uchar int red")); },
                   {"mem.ply", "list"});
  expectInputError([&] { ply(replace(a, "element strand 2", "element strand 0")); },
                   {"mem.ply", "zero strands"});
}

// A file cut anywhere inside its header says "truncated", whatever the cut line's
// remnant would mean ("property " is no "unknown property type ''"); the control, the whole
// header and body, loads.
TEST(PlyParser, CutInsideTheHeaderIsTruncated) {
  const std::string a = kAsciiPly;
  const std::size_t end = a.find("end_header");
  for (std::size_t n = 4; n < end + 10; ++n) {
    SCOPED_TRACE(n);
    expectInputError([&] { ply(text(a.substr(0, n))); }, {"mem.ply", "truncated", "header"});
  }
  EXPECT_EQ(ply(text(a)).strandCount(), 2u);
}

TEST(PlyParser, BadBodies) {
  // Segment counts disagree with the vertex count.
  expectInputError([] { ply(binaryPly(false, 3)); }, {"mem.ply", "nsegs"});
  const std::string a = kAsciiPly;
  std::string bad = a;
  bad.replace(bad.find("2\n1\n"), 4, "2\n2\n");
  expectInputError([&] { ply(text(bad)); }, {"mem.ply", "5 vertices"});
  // NaN and Inf coordinates.
  bad = a;
  bad.replace(bad.find("1 0 0 255"), 1, "nan");
  expectInputError([&] { ply(text(bad)); }, {"mem.ply", "NaN"});
  bad = a;
  bad.replace(bad.find("1 0 0 255"), 1, "inf");
  expectInputError([&] { ply(text(bad)); }, {"mem.ply", "infinite"});
  // Double out of float range becomes infinite.
  Bytes b = binaryPly(false);
  const double huge = 1e300;
  std::memcpy(b.data() + (b.size() - 5 * 24 - 9 - 8), &huge, 8);
  expectInputError([&] { ply(b); }, {"mem.ply", "infinite"});
  // Not a number, out-of-range value for its type.
  bad = a;
  bad.replace(bad.find("1 0 0 255"), 1, "x1");
  expectInputError([&] { ply(text(bad)); }, {"mem.ply", "x1"});
  bad = a;
  bad.replace(bad.find("1 0 0 255"), 9, "1 0 0 256");
  expectInputError([&] { ply(text(bad)); }, {"mem.ply", "256"});
  // Counts larger than the file.
  bad = a;
  bad.replace(bad.find("element vertex 5"), 16, "element vertex 99999999999");
  expectInputError([&] { ply(text(bad)); }, {"mem.ply", "99999999999"});
  Bytes big = binaryPly(false);
  const std::string from = "element vertex 5";
  std::string s(big.begin(), big.end());
  s.replace(s.find(from), from.size(), "element vertex 4000000000");
  expectInputError([&] { ply(text(s)); }, {"mem.ply", "truncated"});
  // Every truncation of the binary file.
  const Bytes full = binaryPly(true);
  for (std::size_t n = 0; n < full.size(); ++n) {
    const Bytes cut(full.begin(), full.begin() + std::ptrdiff_t(n));
    expectInputError([&] { ply(cut); }, {"mem.ply"});
  }
}

// A PLY with no 'strand' element (NeuralHaircut-style): x y z, normals (ignored) and a
// per-strand colour with alpha, strands of perStrand consecutive vertices.
Bytes vertexOnlyPly(bool ascii, uint32_t strands, uint32_t perStrand) {
  const uint32_t n = strands * perStrand;
  std::string h = std::string("ply\nformat ") + (ascii ? "ascii" : "binary_little_endian") +
                  " 1.0\nelement vertex " + std::to_string(n) +
                  "\nproperty float x\nproperty float y\nproperty float z\n"
                  "property float nx\nproperty float ny\nproperty float nz\n"
                  "property uchar red\nproperty uchar green\nproperty uchar blue\n"
                  "property uchar alpha\nend_header\n";
  Bytes b = text(h);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t s = i / perStrand, k = i % perStrand;
    const float xyz[6] = {float(s), float(k), 0.5f, 0, 0, 1};
    const uint8_t rgba[4] = {uint8_t(255 - 40 * (s % 6)), uint8_t(40 * (s % 6)), 0,
                             uint8_t(255 - s % 2 * 127)};
    if (ascii) {
      std::string line;
      for (float f : xyz) line += std::to_string(f) + " ";
      for (uint8_t c : rgba) line += std::to_string(int(c)) + " ";
      line.back() = '\n';
      b.insert(b.end(), line.begin(), line.end());
    } else {
      for (float f : xyz) appendF(b, f);
      b.insert(b.end(), rgba, rgba + 4);
    }
  }
  return b;
}

sb::Strands plyN(const Bytes& b, uint32_t perStrand) {
  return sb::parsePly(b.data(), b.size(), "mem.ply", perStrand);
}

TEST(PlyParser, VertexOnlyWithPointsPerStrand) {
  for (bool ascii : {false, true}) {
    SCOPED_TRACE(ascii ? "ascii" : "binary");
    const sb::Strands s = plyN(vertexOnlyPly(ascii, 3, 4), 4);
    sbtest::expectWellFormed(s);
    ASSERT_EQ(s.strandCount(), 3u);
    for (std::size_t i = 0; i < 3; ++i) {
      EXPECT_EQ(s.pointCount[i], 4u);
      EXPECT_EQ(s.firstPoint[i], 4u * i);
    }
    EXPECT_EQ(s.points[6], glm::vec3(1.0f, 2.0f, 0.5f));  // strand 1, point 2
    // Colour as the strand-element PLYs: uchar sRGB to linear; per strand here.
    EXPECT_NEAR(s.colors[0].x, 1.0f, 1e-6f);
    EXPECT_EQ(s.colors[0].y, 0.0f);
    EXPECT_EQ(s.colors[4], s.colors[7]);
    EXPECT_NE(s.colors[4], s.colors[0]);
    EXPECT_GT(s.colors[4].y, 0.0f);
    // Alpha is opacity: transparency = 1 - alpha (255 opaque, 128 on odd strands).
    EXPECT_FLOAT_EQ(s.transparency[0], 0.0f);
    EXPECT_NEAR(s.transparency[5], 1.0f - 128.0f / 255.0f, 1e-6f);
  }
}

TEST(PlyParser, NeuralHaircutSized) {
  // 190,000 vertices = 1,900 strands x 100 points, binary little endian.
  const sb::Strands s = plyN(vertexOnlyPly(false, 1900, 100), 100);
  sbtest::expectWellFormed(s);
  EXPECT_EQ(s.strandCount(), 1900u);
  EXPECT_EQ(s.points.size(), 190000u);
  EXPECT_EQ(s.segmentCount(), 1900u * 99u);
  EXPECT_EQ(s.points.back(), glm::vec3(1899.0f, 99.0f, 0.5f));
}

TEST(PlyParser, VertexOnlyErrors) {
  const Bytes b = vertexOnlyPly(false, 3, 4);  // 12 vertices
  // Without the option: the message says what to give.
  expectInputError([&] { ply(b); },
                   {"mem.ply", "no 'strand' element", "points_per_strand=", "12 vertices"});
  // Not a whole number of strands: both numbers named.
  expectInputError([&] { plyN(b, 5); }, {"mem.ply", "12 vertices", "points_per_strand=5"});
  expectInputError([&] { plyN(b, 24); }, {"mem.ply", "12 vertices", "points_per_strand=24"});
  // A file with a strand element says where its strands end: the option is refused.
  expectInputError([] { plyN(text(kAsciiPly), 5); }, {"mem.ply", "points_per_strand=5"});
  // Truncated bodies are still errors with the option.
  const Bytes full = vertexOnlyPly(false, 2, 3);
  for (std::size_t n = 0; n < full.size(); n += 5) {
    const Bytes cut(full.begin(), full.begin() + std::ptrdiff_t(n));
    expectInputError([&] { plyN(cut, 3); }, {"mem.ply"});
  }
}

TEST(PlyParser, TriangleMeshPointsToMeshOption) {
  const std::string mesh =
      "ply\nformat ascii 1.0\nelement vertex 3\n"
      "property float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  for (uint32_t n : {0u, 3u}) {  // with or without points_per_strand
    expectInputError([&] { plyN(text(mesh), n); }, {"mem.ply", "mesh", "mesh=", "OBJ"});
  }
}

// ---------------------------------------------------------------- OBJ

TEST(ObjParser, QuadIsTriangulatedAndNormalsComputed) {
  const sb::Mesh m = sb::parseObj("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n", "mem.obj");
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.triangleCount(), 2u);
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(ObjParser, FileNormals) {
  const sb::Mesh m =
      sb::parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 -1\nf 1//1 2//1 3//1\n", "mem.obj");
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, -1.0f, 1e-6f);
}

TEST(ObjParser, Malformed) {
  expectInputError([] { sb::parseObj("", "mem.obj"); }, {"mem.obj"});
  expectInputError([] { sb::parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\n", "mem.obj"); },
                   {"mem.obj", "no faces"});
  expectInputError([] { sb::parseObj("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n", "mem.obj"); },
                   {"mem.obj"});
}

// ---------------------------------------------------------------- meshes (mesh=)

std::string meshData(const char* file) {
  return sbtest::readFile(std::string(SB_SOURCE_DIR) + "/tests/data/meshes/" + file);
}
sb::Mesh plyMesh(const std::string& t) {
  return sb::parsePlyMesh(reinterpret_cast<const uint8_t*>(t.data()), t.size(), "mem.ply");
}
sb::Mesh tfxMesh(const std::string& t) {
  return sb::parseTfxMesh(reinterpret_cast<const uint8_t*>(t.data()), t.size(), "mem.tfxmesh");
}

TEST(MeshLoaders, PlyQuadWithNormalsIsTwoTriangles) {
  const sb::Mesh m = plyMesh(meshData("quad.ply"));
  EXPECT_EQ(m.positions.size(), 4u);
  ASSERT_EQ(m.triangleCount(), 2u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
  // Without normals they are computed; binary bodies read as the strands' do.
  std::string b =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
      "property float y\nproperty float z\nelement face 1\n"
      "property list uchar uint vertex_index\nend_header\n";
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f})
    b.append(reinterpret_cast<char*>(&v), 4);
  b += '\x03';
  for (uint32_t i : {0u, 1u, 2u}) b.append(reinterpret_cast<char*>(&i), 4);
  const sb::Mesh tri = plyMesh(b);
  ASSERT_EQ(tri.triangleCount(), 1u);
  for (const glm::vec3& n : tri.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(MeshLoaders, TfxMeshQuad) {
  const sb::Mesh m = tfxMesh(meshData("quad.tfxmesh"));  // CRLF, '#' comments, bones
  EXPECT_EQ(m.positions.size(), 4u);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(m.positions[2], glm::vec3(1, 1, 0));
  for (const glm::vec3& n : m.normals) EXPECT_NEAR(n.z, 1.0f, 1e-6f);
}

TEST(MeshLoaders, MalformedMeshesNameFileAndProblem) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\n";
  expectInputError([&] { plyMesh(head + "end_header\n0 0 0\n1 0 0\n0 1 0\n"); },
                   {"mem.ply", "no faces"});
  expectInputError(
      [&] {
        plyMesh(head +
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n");
      },
      {"mem.ply", "face 0", "vertex 7"});
  expectInputError(
      [&] {
        plyMesh(head +
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0\n1 0 0\n0 1 0\n3 0 1\n");
      },
      {"mem.ply", "truncated"});
  expectInputError([&] { plyMesh("solid stl\n"); }, {"mem.ply", "not a PLY file"});
  const std::string tfx = meshData("quad.tfxmesh");
  expectInputError([&] { tfxMesh(""); }, {"mem.tfxmesh", "numOfBones"});
  expectInputError([&] { tfxMesh(tfx.substr(0, tfx.find("numOfTriangles"))); },
                   {"mem.tfxmesh", "numOfTriangles"});
  expectInputError([&] { tfxMesh(tfx.substr(0, tfx.find("3 0 1 0 0 0 1"))); },
                   {"mem.tfxmesh", "ends after 3 of the 4 lines of numOfVertices"});
  std::string bad = tfx;
  bad.replace(bad.find("1 0 2 3"), 7, "1 0 2 9");
  expectInputError([&] { tfxMesh(bad); }, {"mem.tfxmesh", "line", "9", "out of range"});
  bad = tfx;
  bad.replace(bad.find("1 1 0 0 0 1"), 3, "1 x");
  expectInputError([&] { tfxMesh(bad); }, {"mem.tfxmesh", "'x' is not a finite number"});
  // Finite as a double, infinite as a float (found by the tfxmesh fuzzer).
  bad = tfx;
  bad.replace(bad.find("1 1 0 0 0 1"), 3, "1 1e300");
  expectInputError([&] { tfxMesh(bad); }, {"mem.tfxmesh", "too large for a float"});
}

// mesh= reads by extension; a file of another format is not called an empty OBJ.
TEST(MeshLoaders, LoadMeshByExtension) {
  const std::string data = std::string(SB_SOURCE_DIR) + "/tests/data/meshes/";
  EXPECT_EQ(sb::loadMesh(data + "quad.ply").triangleCount(), 2u);
  EXPECT_EQ(sb::loadMesh(data + "quad.tfxmesh").triangleCount(), 2u);
  const auto dir = sbtest::tempDir("mesh-ext");
  const std::string stl = (dir / "part.stl").string();
  std::ofstream(stl) << "solid part\nendsolid part\n";
  for (const std::string& scene : {"straight:strands=4,mesh=" + stl, "fur:strands=4,mesh=" + stl})
    expectInputError([&] { sb::makeScene(sb::Spec::parse(scene)); },
                     {stl, "mesh= takes OBJ (.obj), PLY (.ply) and TressFX (.tfxmesh)", "'.stl'"});
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------- file scene options

TEST(FileSceneOptions, PointsPerStrand) {
  const auto dir = sbtest::tempDir("pps");
  const std::string path = (dir / "neural.ply").string();
  const Bytes b = vertexOnlyPly(false, 5, 8);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
  const sb::Scene s = sb::makeScene(sb::Spec::parse("file:path=" + path + ",points_per_strand=8"));
  sbtest::expectWellFormed(s.strands);
  EXPECT_EQ(s.strands.strandCount(), 5u);
  EXPECT_EQ(s.strands.points.size(), 40u);
  EXPECT_TRUE(s.warnings.empty());
  // strands= keeps working on top of it.
  EXPECT_EQ(sb::makeScene(sb::Spec::parse("file:path=" + path + ",points_per_strand=8,strands=2"))
                .strands.strandCount(),
            2u);
  expectInputError([&] { sb::makeScene(sb::Spec::parse("file:path=" + path)); },
                   {path, "points_per_strand="});
  expectInputError(
      [&] { sb::makeScene(sb::Spec::parse("file:path=" + path + ",points_per_strand=3")); },
      {path, "40 vertices", "points_per_strand=3"});
  expectInputError(
      [&] { sb::makeScene(sb::Spec::parse("file:path=" + path + ",points_per_strand=1")); },
      {"points_per_strand=1", "range"});
  expectInputError(
      [&] { sb::makeScene(sb::Spec::parse("file:path=" + path + ",points_per_strand=x")); },
      {"points_per_strand=x"});
  // Only PLY files take it.
  const std::string hairPath = (dir / "a.hair").string();
  expectInputError(
      [&] { sb::makeScene(sb::Spec::parse("file:path=" + hairPath + ",points_per_strand=8")); },
      {hairPath, "points_per_strand=", ".ply"});
  // Declared for `strandbench list`.
  bool listed = false;
  for (const sb::SceneInfo& info : sb::sceneCatalog())
    if (info.name == "file")
      for (const sb::OptionInfo& o : info.options) listed |= o.name == "points_per_strand";
  EXPECT_TRUE(listed);
  std::filesystem::remove_all(dir);
}

// A PLY file says nothing of which way is up: up=auto turns it so that the strands' roots
// lie above their tips (hanging hair), and says so; where roots and tips give no clear
// direction, y. Written here: three strands of 4 points, roots at `root`, tips at `tip`
// (offset per strand), as a NeuralHaircut file of points_per_strand=4 would hold them.
TEST(FileSceneOptions, UpAutoTurnsAPlyByItsRootsAndTips) {
  const auto dir = sbtest::tempDir("up-auto");
  auto write = [&](const std::string& name, glm::vec3 root, glm::vec3 tip) {
    std::string t =
        "ply\nformat ascii 1.0\nelement vertex 12\nproperty float x\nproperty float y\n"
        "property float z\nend_header\n";
    for (int s = 0; s < 3; ++s)
      for (int k = 0; k < 4; ++k) {
        const glm::vec3 p = root + (tip - root) * (float(k) / 3.0f) + glm::vec3(0.1f * s, 0, 0);
        t += std::to_string(p.x) + " " + std::to_string(p.y) + " " + std::to_string(p.z) + "\n";
      }
    const std::string path = (dir / name).string();
    std::ofstream(path, std::ios::binary) << t;
    return "file:path=" + path + ",points_per_strand=4";
  };
  struct Case {
    const char* name;
    glm::vec3 root, tip;
    const char* up;
    const char* why;
  };
  for (const Case& c :
       {Case{"hanging.ply", {0, 1, 0}, {0, 0, 0}, "y", "roots lie above"},
        Case{"upside-down.ply", {0, 0, 0}, {0, 1, 0.2f}, "-y", "roots lie above"},
        Case{"z-up.ply", {0, 0.1f, 1}, {0, 0, 0}, "z", "roots lie above"},
        Case{"sideways.ply", {0, 0, 0}, {1, 0.05f, 0}, "y", "no clear direction"}}) {
    SCOPED_TRACE(c.name);
    const sb::Scene s = sb::makeScene(sb::Spec::parse(write(c.name, c.root, c.tip)));
    EXPECT_EQ(s.up, c.up);
    EXPECT_NE(s.upReason.find(c.why), std::string::npos) << s.upReason;
    EXPECT_NE(s.upReason.find("auto"), std::string::npos) << s.upReason;
    if (std::string(c.why) == "roots lie above") {  // turned: the root above the tip in +y
      EXPECT_GT(s.strands.points[0].y, s.strands.points[3].y);
    }
  }
  // Asked for: kept as given, even upside down (the control: auto turns it).
  const sb::Scene asked =
      sb::makeScene(sb::Spec::parse(write("asked.ply", {0, 0, 0}, {0, 1, 0}) + ",up=y"));
  EXPECT_EQ(asked.up, "y");
  EXPECT_EQ(asked.upReason, "up=y asked for");
  EXPECT_LT(asked.strands.points[0].y, asked.strands.points[3].y);
  // The formats that say keep their axis: generated scenes have none to say.
  EXPECT_EQ(sb::makeScene(sb::Spec::parse("straight:strands=2")).up, "");
  std::filesystem::remove_all(dir);
}

// TressFX and PLY files give no thickness: the loaders' stand-in is marked as one (the
// render JSON's scene.thickness_source "fallback"); HAIR files and generated scenes give one.
TEST(FileSceneOptions, ThicknessTheFileDidNotGiveIsAFallback) {
  const sb::Strands p = ply(text(kAsciiPly));
  EXPECT_TRUE(p.thicknessFallback);
  EXPECT_FLOAT_EQ(p.thickness[0], 0.005f);  // still drawn where a technique reads it
  EXPECT_TRUE(tfx(tfxWithUvs(0)).thicknessFallback);
  EXPECT_FALSE(hair(smallHair()).thicknessFallback);
  EXPECT_FALSE(sb::makeScene(sb::Spec::parse("curly:strands=2")).strands.thicknessFallback);
  // Kept through strands= and zero_segments=, which rebuild the strands.
  const auto dir = sbtest::tempDir("thickness");
  const std::string path = (dir / "a.ply").string();
  std::ofstream(path, std::ios::binary) << kAsciiPly;
  EXPECT_TRUE(sb::makeScene(sb::Spec::parse("file:path=" + path + ",strands=1,zero_segments=1"))
                  .strands.thicknessFallback);
  std::filesystem::remove_all(dir);
}

TEST(FileSceneOptions, CutTfxBlockBecomesASceneWarning) {
  const auto dir = sbtest::tempDir("tfxwarn");
  const std::string path = (dir / "cut.tfx").string();
  const Bytes b = tfxWithUvs(10);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
  const sb::Scene s = sb::makeScene(sb::Spec::parse("file:path=" + path));
  EXPECT_EQ(s.strands.strandCount(), 3u);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find(path), std::string::npos) << s.warnings[0];
  EXPECT_NE(s.warnings[0].find("strand UV"), std::string::npos) << s.warnings[0];
  std::filesystem::remove_all(dir);
}

// ---------------------------------------------------------------- robustness smoke test

// Random bytes and random mutations of valid files: every parser must either succeed
// or throw InputError (run under SB_SANITIZE for over-reads).
TEST(LoaderRobustness, RandomAndMutatedInputs) {
  std::mt19937 rng(12345);
  const std::vector<Bytes> seeds = {smallHair(),
                                    smallTfx(3),
                                    smallTfx(4),
                                    binaryPly(false),
                                    binaryPly(true),
                                    text(kAsciiPly),
                                    text(kTextTfx),
                                    vertexOnlyPly(false, 3, 4),
                                    vertexOnlyPly(true, 2, 3)};
  using Parser = std::function<sb::Strands(const uint8_t*, std::size_t, const std::string&)>;
  const Parser parsers[4] = {sb::parseHair,
                             [](const uint8_t* d, std::size_t n, const std::string& name) {
                               std::vector<std::string> warnings;
                               return sb::parseTfx(d, n, name, &warnings);
                             },
                             [](const uint8_t* d, std::size_t n, const std::string& name) {
                               return sb::parsePly(d, n, name);
                             },
                             [](const uint8_t* d, std::size_t n, const std::string& name) {
                               return sb::parsePly(d, n, name, 4);
                             }};
  for (int iter = 0; iter < 3000; ++iter) {
    Bytes b = seeds[std::size_t(iter) % seeds.size()];
    const int edits = 1 + int(rng() % 8);
    for (int e = 0; e < edits && !b.empty(); ++e) {
      const std::size_t at = rng() % b.size();
      switch (rng() % 4) {
        case 0:
          b[at] = uint8_t(rng());
          break;
        case 1:
          b.resize(at);
          break;
        case 2:
          b[at] = 0xff;
          break;
        default:
          b.insert(b.begin() + std::ptrdiff_t(at), uint8_t(rng()));
          break;
      }
    }
    if (iter % 10 == 0) {
      b.resize(rng() % 300);
      for (uint8_t& x : b) x = uint8_t(rng());
    }
    for (const Parser& p : parsers) {
      try {
        const sb::Strands s = p(b.data(), b.size(), "fuzz.bin");
        sbtest::expectWellFormed(s);
      } catch (const sb::InputError& err) {
        ASSERT_NE(std::string(err.what()).find("fuzz.bin"), std::string::npos) << err.what();
      }
    }
  }
}

}  // namespace
