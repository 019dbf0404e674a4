// Scene specs, generators, validation messages, bounds, camera and light fitting.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <numbers>
#include <set>
#include <string>
#include <tuple>

#include "scenes/scene.h"
#include "scenes/view.h"
#include "test_util.h"

using sbtest::expectInputError;

namespace {

sb::Scene make(const std::string& spec) { return sb::makeScene(sb::Spec::parse(spec)); }

void expectSpecError(const std::string& spec, const std::string& needle) {
  expectInputError([&] { sb::Spec::parse(spec); }, {needle});
}

void expectSceneError(const std::string& spec, std::vector<std::string> needles) {
  expectInputError([&] { make(spec); }, std::move(needles));
}

void checkStrands(const sb::Strands& s) {
  ASSERT_NO_FATAL_FAILURE(sbtest::expectWellFormed(s));
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const glm::vec3& c = s.colors[i];
    ASSERT_TRUE(c.r >= 0 && c.r <= 1 && c.g >= 0 && c.g <= 1 && c.b >= 0 && c.b <= 1);
    ASSERT_GT(s.thickness[i], 0.0f);
    ASSERT_EQ(s.transparency[i], 0.0f);
  }
}

// ---------------------------------------------------------------- Spec

TEST(Spec, NameOnly) {
  const sb::Spec s = sb::Spec::parse("straight");
  EXPECT_EQ(s.name, "straight");
  EXPECT_TRUE(s.options.empty());
  EXPECT_EQ(s.str(), "straight");
  EXPECT_TRUE(sb::Spec::parse("straight:").options.empty());
}

TEST(Spec, Options) {
  const sb::Spec s = sb::Spec::parse("curly:strands=20000,points=32,seed=7");
  EXPECT_EQ(s.name, "curly");
  ASSERT_EQ(s.options.size(), 3u);
  EXPECT_EQ(s.options.at("strands"), "20000");
  EXPECT_EQ(s.options.at("points"), "32");
  EXPECT_EQ(s.options.at("seed"), "7");
}

TEST(Spec, PathsMayContainColonsSlashesAndEquals) {
  const sb::Spec s = sb::Spec::parse("file:path=C:/models/a:b=c.hair,mesh=../x/y.obj");
  EXPECT_EQ(s.name, "file");
  EXPECT_EQ(s.options.at("path"), "C:/models/a:b=c.hair");
  EXPECT_EQ(s.options.at("mesh"), "../x/y.obj");
}

TEST(Spec, RoundTrips) {
  for (const char* text :
       {"straight", "curly:points=32,seed=7,strands=20000",
        "file:path=../shared/models/straight.hair", "fur:density=3.5,mesh=a:b"}) {
    const sb::Spec a = sb::Spec::parse(text);
    const sb::Spec b = sb::Spec::parse(a.str());
    EXPECT_EQ(a.name, b.name) << text;
    EXPECT_EQ(a.options, b.options) << text;
    EXPECT_EQ(a.str(), b.str());
  }
  EXPECT_EQ(sb::Spec::parse("curly:strands=5,points=3").str(), "curly:points=3,strands=5");
}

TEST(Spec, Errors) {
  expectSpecError("", "empty scene name");
  expectSpecError(":strands=1", "empty scene name");
  expectSpecError("straight:strands", "no '='");
  expectSpecError("straight:strands=1,points", "'points' has no '='");
  expectSpecError("straight:strands=1,strands=2", "'strands' is given more than once");
  expectSpecError("straight:=3", "empty key");
  expectSpecError("straight:strands=1,,points=2", "empty option");
  expectSpecError("straight:strands=1,", "empty option");
}

// ---------------------------------------------------------------- catalog

TEST(Catalog, ListsEverySceneWithOptionsAndHelp) {
  std::set<std::string> names;
  for (const sb::SceneInfo& s : sb::sceneCatalog()) {
    names.insert(s.name);
    EXPECT_FALSE(s.help.empty()) << s.name;
    std::set<std::string> opts;
    for (const sb::OptionInfo& o : s.options) {
      EXPECT_FALSE(o.help.empty()) << s.name << "." << o.name;
      opts.insert(o.name);
    }
    for (const char* common : {"alpha", "shadow_alpha", "mesh"}) {
      EXPECT_TRUE(opts.count(common)) << s.name << " lacks " << common;
    }
    if (s.name != "file") {
      for (const char* common : {"strands", "points", "seed"}) {
        EXPECT_TRUE(opts.count(common)) << s.name << " lacks " << common;
      }
    }
  }
  EXPECT_EQ(names, (std::set<std::string>{"straight", "wavy", "curly", "clustered", "fur", "stray",
                                          "sheet", "file"}));
}

// ---------------------------------------------------------------- generators

TEST(Generators, CountsAndConsistency) {
  for (const char* name : {"straight", "wavy", "curly", "clustered", "fur"}) {
    const sb::Scene s = make(std::string(name) + ":strands=150,points=9");
    SCOPED_TRACE(name);
    checkStrands(s.strands);
    EXPECT_EQ(s.strands.strandCount(), 150u);
    EXPECT_EQ(s.strands.points.size(), 150u * 9u);
    EXPECT_EQ(s.strands.segmentCount(), 150u * 8u);
    EXPECT_FALSE(s.mesh.positions.empty());  // head or fur base sphere
    EXPECT_EQ(s.mesh.normals.size(), s.mesh.positions.size());
    EXPECT_EQ(s.mesh.indices.size() % 3, 0u);
    for (uint32_t i : s.mesh.indices) ASSERT_LT(i, s.mesh.positions.size());
    EXPECT_EQ(s.name, std::string(name) + ":points=9,strands=150");
  }
}

TEST(Generators, DefaultsAreModest) {
  for (const sb::SceneInfo& info : sb::sceneCatalog()) {
    if (info.name == "file") continue;
    const sb::Scene s = make(info.name);
    SCOPED_TRACE(info.name);
    checkStrands(s.strands);
    EXPECT_GT(s.strands.strandCount(), 100u);
    EXPECT_LE(s.strands.points.size(), 200000u);  // well under a second on llvmpipe
    EXPECT_FLOAT_EQ(s.hairAlpha, 1.0f);
    EXPECT_FLOAT_EQ(s.shadowAlpha, 0.5f);
    const sb::Bounds b = s.bounds();
    EXPECT_GT(b.radius(), 0.5f);
    EXPECT_LT(b.radius(), 10.0f);
  }
}

TEST(Generators, DeterministicForASeed) {
  for (const char* name : {"straight", "wavy", "curly", "clustered", "fur"}) {
    SCOPED_TRACE(name);
    const std::string base = std::string(name) + ":strands=200,points=12";
    const sb::Scene a = make(base + ",seed=5");
    const sb::Scene b = make(base + ",seed=5");
    const sb::Scene c = make(base + ",seed=6");
    EXPECT_EQ(a.strands.points, b.strands.points);
    EXPECT_EQ(a.strands.colors, b.strands.colors);
    EXPECT_NE(a.strands.points, c.strands.points);
  }
}

TEST(Generators, HairStartsOnTheScalpAndStaysOutsideTheHead) {
  for (const char* name : {"straight", "wavy", "curly", "clustered"}) {
    SCOPED_TRACE(name);
    const sb::Scene s = make(std::string(name) + ":strands=300");
    for (std::size_t i = 0; i < s.strands.strandCount(); ++i) {
      const glm::vec3 root = s.strands.points[s.strands.firstPoint[i]];
      ASSERT_NEAR(glm::length(root), 1.0f, 1e-3f);
      ASSERT_GT(root.y, -0.25f);  // scalp, not the chin
      for (uint32_t k = 1; k < s.strands.pointCount[i]; ++k) {
        ASSERT_GE(glm::length(s.strands.points[s.strands.firstPoint[i] + k]), 0.999f);
      }
    }
  }
}

TEST(Generators, OptionsChangeTheShape) {
  const sb::Scene straight = make("straight:strands=50,points=20");
  // A zero wave or curl is the straight scene (same seed, same random sequence).
  EXPECT_EQ(make("wavy:strands=50,points=20,amplitude=0").strands.points, straight.strands.points);
  EXPECT_EQ(make("curly:strands=50,points=20,radius=0,length=1.5").strands.points,
            straight.strands.points);
  EXPECT_NE(make("wavy:strands=50,points=20").strands.points, straight.strands.points);
  EXPECT_NE(make("straight:strands=50,points=20,length=0.5").strands.points,
            straight.strands.points);
  EXPECT_TRUE(make("straight:strands=10,head=0").mesh.positions.empty());
  const sb::Scene t = make("straight:strands=10,thickness=0.02,alpha=0.3,shadow_alpha=0.1");
  EXPECT_FLOAT_EQ(t.strands.thickness[0], 0.02f);
  EXPECT_FLOAT_EQ(t.hairAlpha, 0.3f);
  EXPECT_FLOAT_EQ(t.shadowAlpha, 0.1f);
}

TEST(Generators, CurlsHaveTheRequestedRadius) {
  // With many points, a curled strand wanders about `radius` around its draped base.
  const sb::Scene base = make("curly:strands=20,points=200,radius=0");
  const sb::Scene curl = make("curly:strands=20,points=200,radius=0.1");
  float maxDev = 0;
  for (std::size_t i = 0; i < base.strands.points.size(); ++i) {
    maxDev = std::max(maxDev, glm::length(curl.strands.points[i] - base.strands.points[i]));
  }
  EXPECT_GT(maxDev, 0.05f);
  EXPECT_LT(maxDev, 0.2f);
}

TEST(Generators, ClustersAreTight) {
  // One cluster with no spread: every strand follows the guide.
  const sb::Scene one = make("clustered:strands=10,points=8,clusters=1,spread=0");
  for (std::size_t i = 1; i < 10; ++i) {
    for (uint32_t k = 0; k < 8; ++k) {
      EXPECT_NEAR(glm::length(one.strands.points[i * 8 + k] - one.strands.points[k]), 0.0f, 1e-5f);
    }
  }
  // Tips of a clump end closer together than their roots start.
  const sb::Scene s = make("clustered:strands=40,points=8,clusters=2,spread=0.3");
  auto spreadAt = [&](uint32_t k) {
    float d = 0;
    for (std::size_t i = 1; i < 20; ++i) {
      d = std::max(d, glm::length(s.strands.points[i * 8 + k] - s.strands.points[k]));
    }
    return d;
  };
  EXPECT_LT(spreadAt(7), spreadAt(0));
  expectSceneError("clustered:strands=10,clusters=11", {"clusters=11", "strands=10"});
}

TEST(Generators, FurDensityAndDroop) {
  // Unit sphere: area about 4 pi.
  const sb::Scene d = make("fur:density=100,points=4");
  EXPECT_NEAR(double(d.strands.strandCount()), 100.0 * 4.0 * std::numbers::pi, 20.0);
  checkStrands(d.strands);
  // Roots lie on the sphere; with no droop fur points along the normal.
  const sb::Scene f = make("fur:strands=100,points=5,droop=0,length=0.2");
  for (std::size_t i = 0; i < 100; ++i) {
    const glm::vec3 root = f.strands.points[i * 5];
    const glm::vec3 tip = f.strands.points[i * 5 + 4];
    ASSERT_NEAR(glm::length(root), 1.0f, 0.01f);
    ASSERT_GT(glm::dot(glm::normalize(tip - root), glm::normalize(root)), 0.99f);
  }
  // Droop bends fur down.
  const sb::Scene g = make("fur:strands=100,points=5,droop=2,length=0.2");
  float dy0 = 0, dy1 = 0;
  for (std::size_t i = 0; i < 100; ++i) {
    dy0 += f.strands.points[i * 5 + 4].y - f.strands.points[i * 5].y;
    dy1 += g.strands.points[i * 5 + 4].y - g.strands.points[i * 5].y;
  }
  EXPECT_LT(dy1, dy0);
  expectSceneError("fur:density=10,strands=100", {"not both"});
}

TEST(Generators, MeshOption) {
  const std::string obj = std::string(SB_SOURCE_DIR) + "/../shared/models/teapot.obj";
  expectSceneError("straight:strands=10,mesh=/nonexistent/m.obj", {"/nonexistent/m.obj"});
  if (!std::ifstream(obj)) GTEST_SKIP() << "../shared/models not found: " << obj;
  const sb::Scene s = make("straight:strands=10,mesh=" + obj);
  EXPECT_EQ(s.mesh.positions.size(), 3644u);
  const sb::Scene f = make("fur:strands=500,mesh=" + obj);
  EXPECT_EQ(f.strands.strandCount(), 500u);
  EXPECT_EQ(f.mesh.positions.size(), 3644u);
  checkStrands(f.strands);
}

// ---------------------------------------------------------------- validation

TEST(Validation, UnknownSceneListsNamesAndSuggests) {
  expectSceneError("curlly", {"unknown scene 'curlly'", "did you mean 'curly'",
                              "straight, wavy, curly, clustered, fur, stray, sheet, file"});
  expectSceneError("strait:strands=3", {"did you mean 'straight'"});
  try {
    make("zzzzzzzz");
    FAIL();
  } catch (const sb::InputError& e) {
    EXPECT_EQ(std::string(e.what()).find("did you mean"), std::string::npos) << e.what();
  }
}

TEST(Validation, UnknownOptionSuggests) {
  expectSceneError("straight:strnads=10",
                   {"'straight'", "unknown option 'strnads'", "did you mean 'strands'", "points"});
  expectSceneError("curly:radus=0.1", {"did you mean 'radius'"});
  expectSceneError("straight:radius=0.1", {"unknown option 'radius'"});
  expectSceneError("fur:head=0", {"unknown option 'head'"});
}

TEST(Validation, BadValues) {
  expectSceneError("straight:strands=-1", {"strands=-1", "out of range"});
  expectSceneError("straight:strands=0", {"strands=0", "out of range"});
  expectSceneError("straight:strands=abc", {"strands=abc", "not an integer"});
  expectSceneError("straight:strands=10x", {"strands=10x", "not an integer"});
  expectSceneError("straight:strands=2.5", {"not an integer"});
  expectSceneError("straight:strands=", {"strands=", "not an integer"});
  expectSceneError("straight:strands=99999999999999999999999", {"strands=99999999999999999999999"});
  expectSceneError("straight:points=1", {"points=1", "out of range"});
  expectSceneError("straight:seed=-3", {"seed=-3"});
  expectSceneError("straight:alpha=1.5", {"alpha=1.5", "out of range"});
  expectSceneError("straight:alpha=-0.1", {"alpha=-0.1", "out of range"});
  expectSceneError("straight:alpha=nan", {"alpha=nan", "not a finite number"});
  expectSceneError("straight:shadow_alpha=inf", {"shadow_alpha=inf", "finite"});
  expectSceneError("straight:shadow_alpha=x", {"shadow_alpha=x", "not a finite number"});
  expectSceneError("straight:head=2", {"head=2"});
  expectSceneError("straight:length=0", {"length=0"});
  expectSceneError("straight:thickness=-1", {"thickness=-1"});
  expectSceneError("wavy:amplitude=1e40", {"amplitude=1e40"});
  expectSceneError("fur:density=0", {"density=0"});
  expectSceneError("file:path=x.hair,strands=0", {"strands=0"});
  // Absurd allocations are refused before anything is allocated.
  expectSceneError("straight:strands=40000000,points=100", {"exceeds the limit"});
  expectSceneError("fur:density=1e9", {"density="});
}

// ---------------------------------------------------------------- bounds, camera, light

TEST(Bounds, EmptySceneIsAUnitCube) {
  const sb::Scene empty;
  const sb::Bounds b = empty.bounds();
  EXPECT_EQ(b.min, glm::vec3(-0.5f));
  EXPECT_EQ(b.max, glm::vec3(0.5f));
  EXPECT_NEAR(b.radius(), std::sqrt(3.0f) / 2, 1e-6f);
  const sb::Camera cam = sb::fitCamera(b, 1.0f);
  const glm::mat4 m = cam.projection(1.0f) * cam.view();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) EXPECT_TRUE(std::isfinite(m[i][j]));
  }
}

TEST(Bounds, StrandsAndMeshTogether) {
  sb::Scene s;
  s.strands.points = {{0, 0, 0}, {1, 2, 3}};
  s.mesh.positions = {{-1, 0, 0}};
  const sb::Bounds b = s.bounds();
  EXPECT_EQ(b.min, glm::vec3(-1, 0, 0));
  EXPECT_EQ(b.max, glm::vec3(1, 2, 3));
  EXPECT_EQ(b.center(), glm::vec3(0, 1, 1.5f));
}

// Points on the bounding sphere along the axes and the box corners.
std::vector<glm::vec3> sphereSamples(const sb::Bounds& b) {
  const glm::vec3 c = b.center();
  const float r = b.radius();
  std::vector<glm::vec3> pts;
  for (int axis = 0; axis < 3; ++axis) {
    for (float sgn : {-1.0f, 1.0f}) {
      glm::vec3 d(0.0f);
      d[axis] = sgn * r;
      pts.push_back(c + d);
    }
  }
  for (int i = 0; i < 8; ++i) {
    pts.push_back(
        glm::vec3(i & 1 ? b.max.x : b.min.x, i & 2 ? b.max.y : b.min.y, i & 4 ? b.max.z : b.min.z));
  }
  // Points on the sphere in the light's direction, too.
  const glm::vec3 l = glm::normalize(glm::vec3(1, 1.2f, 0.8f));
  pts.push_back(c + l * r);
  pts.push_back(c - l * r);
  return pts;
}

void expectInsideClip(const glm::mat4& viewProj, const std::vector<glm::vec3>& pts) {
  for (const glm::vec3& p : pts) {
    const glm::vec4 clip = viewProj * glm::vec4(p, 1.0f);
    ASSERT_GT(clip.w, 0.0f);
    const glm::vec3 ndc = glm::vec3(clip) / clip.w;
    EXPECT_LE(std::abs(ndc.x), 1.0f + 1e-4f);
    EXPECT_LE(std::abs(ndc.y), 1.0f + 1e-4f);
    EXPECT_GE(ndc.z, -1e-4f);  // depth in [0, 1]
    EXPECT_LE(ndc.z, 1.0f + 1e-4f);
  }
}

TEST(View, FitCameraFramesTheBounds) {
  const sb::Scene scene = make("straight:strands=200");
  const sb::Bounds b = scene.bounds();
  for (float aspect : {1.0f, 16.0f / 9.0f, 0.5f}) {
    const sb::Camera cam = sb::fitCamera(b, aspect);
    EXPECT_EQ(cam.target, b.center());
    EXPECT_GT(cam.eye.z, b.center().z);  // looks along -z
    EXPECT_FLOAT_EQ(cam.eye.x, b.center().x);
    EXPECT_GT(cam.nearPlane, 0.0f);
    EXPECT_LT(cam.nearPlane, cam.farPlane);
    expectInsideClip(cam.projection(aspect) * cam.view(), sphereSamples(b));
  }
  // The center projects to the middle of the screen, nearer than the far plane.
  const sb::Camera cam = sb::fitCamera(b, 1.0f);
  const glm::vec4 clip = cam.projection(1.0f) * cam.view() * glm::vec4(b.center(), 1.0f);
  EXPECT_NEAR(clip.x / clip.w, 0.0f, 1e-5f);
  EXPECT_NEAR(clip.y / clip.w, 0.0f, 1e-5f);
  // No y flip: a point above the center is in the upper half of NDC.
  const glm::vec4 up = cam.projection(1.0f) * cam.view() *
                       glm::vec4(b.center() + glm::vec3(0, 0.5f * b.radius(), 0), 1.0f);
  EXPECT_GT(up.y / up.w, 0.0f);
}

TEST(View, FitLightEnclosesTheBoundsTightly) {
  sb::Bounds b;
  b.min = glm::vec3(-1.0f, 0.5f, -2.0f);
  b.max = glm::vec3(3.0f, 2.0f, 1.0f);
  for (sb::LightType type : {sb::LightType::Directional, sb::LightType::Point}) {
    const sb::Light light = sb::fitLight(b, type);
    EXPECT_EQ(light.type, type);
    EXPECT_NEAR(glm::length(light.direction), 1.0f, 1e-5f);
    EXPECT_LT(light.direction.y, 0.0f);                               // from above
    EXPECT_GT(glm::length(light.position - b.center()), b.radius());  // outside the sphere
    EXPECT_GT(light.nearPlane, 0.0f);
    // Depth range is tight: about the sphere's diameter.
    EXPECT_LT(light.farPlane - light.nearPlane, 2.1f * b.radius());
    expectInsideClip(light.projection() * light.view(), sphereSamples(b));
    if (type == sb::LightType::Directional) {
      EXPECT_NEAR(light.orthoHalfExtent, b.radius(), 0.02f * b.radius());
    } else {
      EXPECT_GT(light.fovYDegrees, 1.0f);
      EXPECT_LT(light.fovYDegrees, 90.0f);
    }
  }
}

TEST(View, DegenerateBoundsStayFinite) {
  sb::Bounds b;
  b.min = b.max = glm::vec3(2, 3, 4);  // a single point
  const sb::Camera cam = sb::fitCamera(b, 1.0f);
  const sb::Light light = sb::fitLight(b, sb::LightType::Point);
  const glm::mat4 m1 = cam.projection(1.0f) * cam.view();
  const glm::mat4 m2 = light.projection() * light.view();
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      EXPECT_TRUE(std::isfinite(m1[i][j]));
      EXPECT_TRUE(std::isfinite(m2[i][j]));
    }
  }
}

}  // namespace

namespace {

TEST(StiffSceneOptions, ScaleZeroSegmentsAndSheet) {
  const sb::Scene base = sb::makeScene(sb::Spec::parse("straight:strands=20,points=5"));
  const sb::Scene big = sb::makeScene(sb::Spec::parse("straight:strands=20,points=5,scale=1e5"));
  EXPECT_NEAR(big.bounds().max.x, base.bounds().max.x * 1e5f, 1e-3f * 1e5f);
  EXPECT_NEAR(big.mesh.positions[0].y, base.mesh.positions[0].y * 1e5f, 1.0f);
  EXPECT_FLOAT_EQ(big.strands.thickness[0], base.strands.thickness[0] * 1e5f);

  const sb::Scene doubled =
      sb::makeScene(sb::Spec::parse("straight:strands=20,points=5,zero_segments=1"));
  sbtest::expectWellFormed(doubled.strands);
  ASSERT_EQ(doubled.strands.points.size(), 2 * base.strands.points.size());
  EXPECT_EQ(doubled.strands.segmentCount(), 20u * 9u);
  EXPECT_EQ(doubled.strands.points[0], doubled.strands.points[1]);  // a zero-length segment

  const sb::Scene sheet = sb::makeScene(sb::Spec::parse("sheet:strands=10,points=6"));
  sbtest::expectWellFormed(sheet.strands);
  for (const glm::vec3& p : sheet.strands.points) EXPECT_EQ(p.z, 0.0f);
  EXPECT_EQ(sheet.strands.strandCount(), 10u);

  sbtest::expectInputError([] { sb::makeScene(sb::Spec::parse("straight:scale=0")); }, {"scale"});
  sbtest::expectInputError([] { sb::makeScene(sb::Spec::parse("straight:zero_segments=2")); },
                           {"zero_segments"});
}

}  // namespace

namespace {

// Where the default camera puts a scene's strand points: their extent in NDC, x and y.
glm::vec2 framedExtent(const sb::Scene& s, float aspect) {
  const sb::Camera cam = sb::fitCamera(s.bounds(), aspect, s.frameByBox);
  const glm::mat4 m = cam.projection(aspect) * cam.view();
  glm::vec2 lo(1e30f), hi(-1e30f);
  for (const glm::vec3& p : s.strands.points) {
    const glm::vec4 c = m * glm::vec4(p, 1.0f);
    EXPECT_GT(c.w, 0.0f);
    const glm::vec2 ndc = glm::vec2(c) / c.w;
    lo = glm::min(lo, ndc);
    hi = glm::max(hi, ndc);
  }
  EXPECT_GE(lo.x, -1.0f);  // inside the frame
  EXPECT_GE(lo.y, -1.0f);
  EXPECT_LE(hi.x, 1.0f);
  EXPECT_LE(hi.y, 1.0f);
  return hi - lo;
}

}  // namespace

// Every strand file in ../shared/models, in its default view: inside the frame and
// filling at least half of its width or height (NDC spans 2).
TEST(SceneFraming, EveryModelFillsHalfTheFrame) {
  const std::filesystem::path models =
      std::filesystem::path(SB_SOURCE_DIR) / ".." / "shared" / "models";
  if (!std::filesystem::exists(models)) GTEST_SKIP() << "../shared/models not found: " << models;
  int files = 0;
  for (const auto& e : std::filesystem::directory_iterator(models)) {
    const std::string ext = e.path().extension().string();
    if (ext != ".hair" && ext != ".tfx" && ext != ".ply") continue;
    SCOPED_TRACE(e.path().filename().string());
    ++files;
    const sb::Scene s = make("file:path=" + e.path().string());
    for (float aspect : {1.0f, 16.0f / 9.0f}) {
      const glm::vec2 extent = framedExtent(s, aspect);
      EXPECT_GE(std::max(extent.x, extent.y), 1.0f) << "aspect " << aspect;
    }
  }
  EXPECT_GE(files, 4);
}

// Yuksel's .hair models are z-up: loaded with up=auto, the roots are above the tips
// (the hair hangs, seen from the front, not from above onto the parting); up=y keeps
// the file's axes, and the sphere fit of a generated scene is unchanged.
TEST(SceneFraming, HairFilesAreTurnedZUp) {
  const std::string hair = std::string(SB_SOURCE_DIR) + "/../shared/models/straight.hair";
  if (!std::ifstream(hair)) GTEST_SKIP() << "../shared/models not found: " << hair;
  auto rootsAboveTips = [](const sb::Scene& s) {
    double roots = 0, tips = 0;
    for (std::size_t i = 0; i < s.strands.strandCount(); ++i) {
      roots += s.strands.points[s.strands.firstPoint[i]].y;
      tips += s.strands.points[s.strands.firstPoint[i] + s.strands.pointCount[i] - 1].y;
    }
    return roots - tips;
  };
  EXPECT_GT(rootsAboveTips(make("file:path=" + hair + ",strands=500")), 0.0);
  const sb::Scene asIs = make("file:path=" + hair + ",strands=500,up=y");
  const sb::Scene turned = make("file:path=" + hair + ",strands=500,up=z");
  ASSERT_EQ(asIs.strands.points.size(), turned.strands.points.size());
  EXPECT_EQ(turned.strands.points[7].y, asIs.strands.points[7].z);
  EXPECT_EQ(turned.strands.points[7].z, -asIs.strands.points[7].y);
  EXPECT_FALSE(make("curly:strands=10").frameByBox);
}

TEST(SceneFraming, ColorOverridesTheFilesColours) {
  const std::string ply = std::string(SB_SOURCE_DIR) + "/../shared/models/Curly_100.ply";
  expectSceneError("file:path=x.hair,color=1/2", {"color=1/2", "R/G/B"});
  expectSceneError("file:path=x.hair,color=0.1/0.2/1.5", {"color=0.1/0.2/1.5"});
  expectSceneError("file:path=x.hair,color=red", {"color=red"});
  if (!std::ifstream(ply)) GTEST_SKIP() << "../shared/models not found: " << ply;
  const sb::Scene own = make("file:path=" + ply);
  std::set<std::tuple<float, float, float>> colours;
  for (const glm::vec3& c : own.strands.colors) colours.insert({c.x, c.y, c.z});
  EXPECT_GT(colours.size(), 10u);  // the file's (CT2Hair's per-strand colours)
  const sb::Scene grey = make("file:path=" + ply + ",color=0.5/0.4/0.3");
  for (const glm::vec3& c : grey.strands.colors) EXPECT_EQ(c, glm::vec3(0.5f, 0.4f, 0.3f));
}
