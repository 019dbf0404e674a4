// The CPU strand references over Embree (`--reference pbr:...`, docs/physics-reference.md):
// the transmittance mode agrees with the rasterized exact reference on wide ribbons (synthetic
// and real strands; a shadow map fails the same bound), thin lines differ by their footprint,
// the cache is reused and keyed, the path mode's noise falls with spp, bad specs are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>

#include "harness/pbr_reference.h"
#include "harness/reference_spec.h"
#include "harness/render.h"
#include "imaging/metrics.h"
#include "pbr/strand_tracer.h"
#include "test_util.h"

namespace {

namespace fs = std::filesystem;

const std::string kModels = std::string(SB_SOURCE_DIR) + "/../shared/models";

// A cache folder of the test's own (removed when it ends), or none.
struct CacheDir {
  fs::path dir;
  explicit CacheDir(const std::string& name) {
    dir = fs::temp_directory_path() / ("sb-pbr-" + name + "-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    ::setenv("SB_PBR_CACHE", dir.c_str(), 1);
  }
  ~CacheDir() {
    fs::remove_all(dir);
    ::unsetenv("SB_PBR_CACHE");
  }
};

sb::RenderRequest pbrRequest(const std::string& scene, const std::string& shadow,
                             const std::string& primitive, float ribbonWidth,
                             const std::string& pbrSpec, const std::string& backend = "gl",
                             const std::string& shading = "") {
  sb::RenderRequest r;
  r.backend = backend;
  if (!shading.empty()) r.shading = shading;
  r.scene = scene;
  r.shadow = shadow;
  r.width = r.height = 64;
  r.primitive = primitive;
  r.ribbonWidth = ribbonWidth;
  r.warmup = 0;
  r.reference = true;
  r.references = {pbrSpec};
  return r;
}

// Mean over the interior pixels a strand covers (no different eye fragment count in the 3x3
// neighbourhood: a ribbon's edge is not within the pixel) of the largest channel difference.
struct Interior {
  double mean = 0;
  double reference = 0;  // the mean of b's largest channel over the same pixels
  int covered = 0;
};
Interior interiorDifference(const sb::RenderResult& out, const sb::Image& a, const sb::Image& b,
                            bool interiorOnly) {
  const int w = a.width, h = a.height;
  const std::vector<uint32_t>& counts = out.eyeComplexity->counts;  // bottom-up
  auto count = [&](int x, int y) { return counts[std::size_t(h - 1 - y) * w + x]; };
  Interior r;
  double sum = 0, refSum = 0;
  for (int y = 1; y + 1 < h; ++y)
    for (int x = 1; x + 1 < w; ++x) {
      bool edge = false;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) edge = edge || count(x + dx, y + dy) != count(x, y);
      if ((edge && interiorOnly) || count(x, y) == 0) continue;
      double pixel = 0, ref = 0;
      for (int c = 0; c < 3; ++c) {
        pixel = std::max(
            pixel, double(std::fabs(a.pixels[a.index(x, y, c)] - b.pixels[b.index(x, y, c)])));
        ref = std::max(ref, double(b.pixels[b.index(x, y, c)]));
      }
      sum += pixel;
      refSum += ref;
      ++r.covered;
    }
  r.mean = r.covered ? sum / r.covered : 0.0;
  r.reference = r.covered ? refSum / r.covered : 0.0;
  return r;
}

// Why `backend` cannot render here, or "" (the skip's words count as a set-up failure in CI).
std::string backendMissing(const std::string& backend) {
  try {
    sb::RenderRequest r =
        pbrRequest("straight:strands=2,points=3", "exact", "lines", 1, "exact", backend);
    r.references.clear();
    sb::runRender(r);
    return "";
  } catch (const sb::DeviceError& e) {
    return backend + " backend unavailable: " + e.what();
  }
}
// The transmittance reference against the exact reference (and, the control, the image with
// no shadows against the transmittance reference) over the pixels of ribbons 6 pixels wide
// (interiorOnly: away from their edges), light maps of 256 texels (ribbons 6 texels wide there).
void expectAgreement(const std::string& scene, double tolerance, bool interiorOnly,
                     const std::string& backend) {
  SCOPED_TRACE(backend);
  CacheDir cache("agree");
  const sb::RenderResult out = sb::runRender(
      pbrRequest(scene, "none", "ribbons", 6.0f, "pbr:mode=transmittance,spp=1", backend));
  ASSERT_EQ(out.moreReferences.size(), 1u);
  ASSERT_TRUE(out.eyeComplexity);
  const sb::Image& pbr = out.moreReferences[0].referenceImage;
  const Interior agree = interiorDifference(out, out.referenceImage, pbr, interiorOnly);
  const Interior control = interiorDifference(out, out.image, pbr, interiorOnly);
  std::cout << "[ measured ] " << backend << ", " << scene << ": " << agree.covered
            << " interior covered pixels, mean max-channel |exact - pbr| " << agree.mean
            << "; control (no shadows - pbr) " << control.mean << "; whole-image RMSE "
            << sb::compareImages(out.referenceImage, pbr).rmse << "\n";
  EXPECT_GT(agree.covered, 30);
  EXPECT_LE(agree.mean, tolerance);
  EXPECT_GT(control.mean, tolerance);  // the control fails the bound
}

// The raster reference on both APIs (the CPU reference is the same for both).
TEST(PbrReference, TransmittanceAgreesWithTheExactReferenceOnWideSyntheticRibbons) {
  for (const std::string backend : {"gl", "vulkan"}) {
    if (const std::string why = backendMissing(backend); !why.empty()) GTEST_SKIP() << why;
    expectAgreement("straight:strands=12,points=5,seed=5,head=1", 0.03, true, backend);
  }
}

// 150 strands of straight.hair as 6-pixel ribbons, edges included. What is left: ribbons'
// ends and joins where strands bend towards the eye, and depth ties between crossing strands.
TEST(PbrReference, TransmittanceAgreesWithTheExactReferenceOnARealGroom) {
  if (!fs::exists(kModels + "/straight.hair")) GTEST_SKIP() << "../shared/models not found";
  for (const std::string backend : {"gl", "vulkan"}) {
    if (const std::string why = backendMissing(backend); !why.empty()) GTEST_SKIP() << why;
    expectAgreement("file:path=" + kModels + "/straight.hair,strands=150", 0.03, false, backend);
  }
}

// The chiang shading model's GLSL (the raster's exact reference, on each API) against its CPU
// form (HairShading::direct, which the transmittance reference shades with) over the interior
// pixels of 6-pixel ribbons, relative to the CPU image's level there; the control, the GPU
// image of the model with its tilt mirrored, fails the same bound.
TEST(PbrReference, ChiangShadingOnBothApisMatchesItsCpuForm) {
  const std::string scene = "straight:strands=12,points=5,seed=5,head=1";
  // 7e-5 measured on llvmpipe and lavapipe (the control: 0.76).
  constexpr double kTolerance = 0.002;
  for (const std::string backend : {"gl", "vulkan"}) {
    if (const std::string why = backendMissing(backend); !why.empty()) GTEST_SKIP() << why;
    SCOPED_TRACE(backend);
    CacheDir cache("chiang");
    const std::string spec = "pbr:mode=transmittance,spp=1";
    const sb::RenderResult out =
        sb::runRender(pbrRequest(scene, "none", "ribbons", 6.0f, spec, backend, "chiang"));
    const sb::RenderResult mirrored =
        sb::runRender(pbrRequest(scene, "none", "ribbons", 6.0f, spec, backend, "chiang:alpha=-2"));
    ASSERT_EQ(out.moreReferences.size(), 1u);
    const sb::Image& cpu = out.moreReferences[0].referenceImage;
    const Interior agree = interiorDifference(out, out.referenceImage, cpu, true);
    const Interior control = interiorDifference(out, mirrored.referenceImage, cpu, true);
    const double rel = agree.mean / agree.reference, relControl = control.mean / agree.reference;
    std::cout << "[ measured ] " << backend << ": " << agree.covered
              << " interior pixels, mean max-channel |gpu - cpu| / cpu level " << rel << " (level "
              << agree.reference << "); control (tilt mirrored) " << relControl << "\n";
    EXPECT_GT(agree.covered, 30);
    EXPECT_GT(agree.reference, 0.0);
    EXPECT_LE(rel, kTolerance);
    EXPECT_GT(relControl, kTolerance);
  }
}

TEST(PbrReference, ThinLinesDifferByTheirFootprint) {
  if (const std::string why = backendMissing("gl"); !why.empty()) GTEST_SKIP() << why;
  // One-pixel lines: the rasterizer's diamond rule decides a pixel, the ray a one-pixel ribbon
  // about the centre; world widths (thickness 0.005, a tenth of a pixel) cover few pixel
  // centres at all. The footprint model is the larger part of the difference.
  CacheDir cache("thin");
  const std::string scene = "straight:strands=12,points=5,seed=5,head=0";
  const sb::RenderResult fp = sb::runRender(
      pbrRequest(scene, "exact:size=256", "lines", 1, "pbr:mode=transmittance,width=footprint"));
  const sb::RenderResult world = sb::runRender(
      pbrRequest(scene, "exact:size=256", "lines", 1, "pbr:mode=transmittance,width=world"));
  const double a = fp.moreReferences.at(0).image.rmse, b = world.moreReferences.at(0).image.rmse;
  std::cout << "[ measured ] lines: RMSE exact vs pbr footprint " << a << ", vs pbr world " << b
            << "\n";
  EXPECT_LT(a, b);
}

TEST(PbrReference, CacheIsReusedAndKeyed) {
  if (const std::string why = backendMissing("gl"); !why.empty()) GTEST_SKIP() << why;
  CacheDir cache("cache");
  const sb::RenderRequest r =
      pbrRequest("straight:strands=12,points=5,head=0", "exact", "lines", 1, "pbr:mode=path,spp=4");
  const sb::RenderResult first = sb::runRender(r);
  const sb::RenderResult second = sb::runRender(r);
  ASSERT_TRUE(first.moreReferences.at(0).pbr && second.moreReferences.at(0).pbr);
  EXPECT_FALSE(first.moreReferences[0].pbr->cacheHit);
  EXPECT_TRUE(second.moreReferences[0].pbr->cacheHit);
  EXPECT_TRUE(fs::exists(second.moreReferences[0].pbr->file));
  EXPECT_EQ(first.moreReferences[0].referenceImage.pixels,
            second.moreReferences[0].referenceImage.pixels);
  // Another seed (or scene, light, size) is another key: rendered again.
  sb::RenderRequest other = r;
  other.references = {"pbr:mode=path,spp=4,seed=2"};
  const sb::RenderResult third = sb::runRender(other);
  EXPECT_FALSE(third.moreReferences.at(0).pbr->cacheHit);
  EXPECT_NE(third.moreReferences[0].pbr->key, first.moreReferences[0].pbr->key);
}

TEST(PbrReference, PathNoiseFallsWithSamplesAndIsDeterministic) {
  if (const std::string why = backendMissing("gl"); !why.empty()) GTEST_SKIP() << why;
  ::setenv("SB_PBR_CACHE", "off", 1);
  auto run = [](int spp) {
    return sb::runRender(pbrRequest("straight:strands=30,points=5,head=1,thickness=0.05", "exact",
                                    "lines", 1, "pbr:mode=path,spp=" + std::to_string(spp)))
        .moreReferences.at(0);
  };
  const auto a = run(4), b = run(16), again = run(16);
  ::unsetenv("SB_PBR_CACHE");
  std::cout << "[ measured ] path noise RMSE at 4 spp " << a.pbr->noiseRmse << ", at 16 "
            << b.pbr->noiseRmse << "\n";
  EXPECT_GT(a.pbr->noiseRmse, 0.0);
  EXPECT_LT(b.pbr->noiseRmse, a.pbr->noiseRmse * 0.75);  // about 1/2 expected
  EXPECT_EQ(b.referenceImage.pixels, again.referenceImage.pixels);
}

TEST(PbrReference, SpecsParseAndBadOnesAreRefused) {
  const sb::ReferenceSpec s = sb::parseReferenceSpec("pbr:mode=transmittance,spp=4,bounces=2");
  EXPECT_EQ(s.mode, "transmittance");
  EXPECT_EQ(s.spp, 4);
  EXPECT_EQ(sb::parseReferenceSpec(s.str()), s);
  EXPECT_EQ(sb::pbrWidthModel(s), "footprint");
  EXPECT_EQ(sb::pbrWidthModel(sb::parseReferenceSpec("pbr")), "world");
  EXPECT_THROW(sb::parseReferenceSpec("pbr:mode=volume"), sb::InputError);
  EXPECT_THROW(sb::parseReferenceSpec("pbr:spp=0"), sb::InputError);
  EXPECT_THROW(sb::parseReferenceSpec("pbr:bounces=65"), sb::InputError);
  EXPECT_THROW(sb::parseReferenceSpec("pbr:samples=4"), sb::InputError);
}

}  // namespace

// Embree's curves, as the tracer uses them: a strand passing next to the ray's origin is found
// (Embree alone misses one within about its radius: here every hit on the first strand), and a
// ray past a strand's end, within the radius Embree caps it with, finds nothing.
TEST(StrandTracer, FindsStrandsNextToItsOriginAndNoneBeyondTheirEnds) {
  sb::pbr::TraceGeometry g;
  g.firstPoint = {0, 3};
  g.pointCount = {3, 2};
  g.points = {{0, 0, 0}, {0, 1, 0}, {0, 2, 0}, {-1, 0.5f, -0.3f}, {1, 0.5f, -0.3f}};
  g.radius.assign(g.points.size(), 0.25f);
  const sb::pbr::StrandTracer tracer(g);
  for (float z : {0.3f, 0.1f, 0.0f}) {
    const sb::pbr::RayHits h = tracer.trace({0.05f, 0.5f, z}, {0, 0, -1}, 0.0f, 100.0f);
    ASSERT_EQ(h.strands.size(), 2u) << "origin " << z << " in front of the first strand";
    EXPECT_EQ(h.strands[0].segment, 0u);
    EXPECT_NEAR(h.strands[0].t, z, 1e-4f);
    EXPECT_EQ(h.strands[1].segment, 2u);
    EXPECT_NEAR(h.strands[1].t, z + 0.3f, 1e-4f);
  }
  EXPECT_TRUE(tracer.trace({0, 2.2f, 1}, {0, 0, -1}, 0.0f, 100.0f).strands.empty());
  EXPECT_EQ(tracer.trace({0, 1.9f, 1}, {0, 0, -1}, 0.0f, 100.0f).strands.size(), 1u);  // control
}
