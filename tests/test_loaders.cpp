// Loader tests: the real models in ../shared/models (skipped when absent) and
// malformed inputs built in memory.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

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

TEST(RealModels, BunnyObj) {
  REQUIRE_MODEL("stanford-bunny.obj");
  const sb::Mesh m = sb::loadObj(path);
  EXPECT_EQ(m.positions.size(), 35947u);
  EXPECT_EQ(m.triangleCount(), 69451u);
  ASSERT_EQ(m.normals.size(), m.positions.size());
  for (const glm::vec3& n : m.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f);
}

TEST(RealModels, TeapotObj) {
  REQUIRE_MODEL("teapot.obj");
  const sb::Mesh m = sb::loadObj(path);
  EXPECT_EQ(m.positions.size(), 3644u);
  EXPECT_EQ(m.triangleCount(), 6320u);
  for (uint32_t i : m.indices) ASSERT_LT(i, m.positions.size());
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

// ---------------------------------------------------------------- PLY builder

Bytes text(const std::string& s) { return Bytes(s.begin(), s.end()); }
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

// ---------------------------------------------------------------- robustness smoke test

// Random bytes and random mutations of valid files: every parser must either succeed
// or throw InputError (run under SB_SANITIZE for over-reads).
TEST(LoaderRobustness, RandomAndMutatedInputs) {
  std::mt19937 rng(12345);
  const std::vector<Bytes> seeds = {smallHair(),      smallTfx(3),     smallTfx(4),
                                    binaryPly(false), binaryPly(true), text(kAsciiPly)};
  using Parser = sb::Strands (*)(const uint8_t*, std::size_t, const std::string&);
  const Parser parsers[3] = {sb::parseHair, sb::parseTfx, sb::parsePly};
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
    for (Parser p : parsers) {
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
