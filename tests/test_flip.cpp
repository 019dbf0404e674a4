// FLIP (imaging/flip.h): its stages, its properties on synthetic strand
// images, agreement with NVIDIA's reference implementation on a committed
// rendered pair, and `strandbench compare`'s FLIP fields.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "base/errors.h"
#include "imaging/flip.h"
#include "imaging/image.h"
#include "imaging/metrics.h"

namespace fs = std::filesystem;

namespace {

// A synthetic strand image: `strands` gently curved, mostly vertical strands,
// each one pixel wide with an antialiased (triangle) footprint, composited with
// alpha 0.8 over a grey-blue background, in display values. Strand i is drawn
// unless drawn[i] is false; all are shifted right by `shift` pixels.
struct StrandPicture {
  int width = 128, height = 128, strands = 24;
  unsigned seed = 5;
  double shift = 0.0;
  std::vector<bool> drawn;

  struct Strand {
    double x0, amplitude, period, phase;
    float r, g, b;
  };

  std::vector<Strand> layout() const {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    std::vector<Strand> s;
    for (int i = 0; i < strands; ++i)
      s.push_back({8.0 + u(rng) * (width - 16), 2.0 + 4.0 * u(rng), 40.0 + 60.0 * u(rng),
                   6.28 * u(rng), static_cast<float>(0.45 + 0.3 * u(rng)),
                   static_cast<float>(0.25 + 0.2 * u(rng)),
                   static_cast<float>(0.1 + 0.1 * u(rng))});
    return s;
  }

  // Horizontal centre of strand s at height y + 0.5.
  double centre(const Strand& s, int y) const {
    return s.x0 + shift + s.amplitude * std::sin(6.28318 * (y + 0.5) / s.period + s.phase);
  }

  // Coverage of pixel (x, y) by strand s.
  double coverage(const Strand& s, int x, int y) const {
    return std::max(0.0, 1.0 - std::fabs(x + 0.5 - centre(s, y)));
  }

  sb::Image image() const {
    sb::Image img(width, height, 4, 1.0f);
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        img.at(x, y, 0) = 0.30f;
        img.at(x, y, 1) = 0.33f;
        img.at(x, y, 2) = 0.40f;
      }
    const auto all = layout();
    for (std::size_t i = 0; i < all.size(); ++i) {
      if (i < drawn.size() && !drawn[i]) continue;
      const Strand& s = all[i];
      for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
          const float a = static_cast<float>(0.8 * coverage(s, x, y));
          if (a <= 0.0f) continue;
          img.at(x, y, 0) = img.at(x, y, 0) * (1 - a) + s.r * a;
          img.at(x, y, 1) = img.at(x, y, 1) * (1 - a) + s.g * a;
          img.at(x, y, 2) = img.at(x, y, 2) * (1 - a) + s.b * a;
        }
    }
    return img;
  }
};

StrandPicture withoutFirst(int removed) {
  StrandPicture p;
  p.drawn.assign(static_cast<std::size_t>(p.strands), true);
  for (int i = 0; i < removed; ++i) p.drawn[static_cast<std::size_t>(i)] = false;
  return p;
}

sb::Image scaled(sb::Image img, float k) {
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    if (i % 4 != 3) img.pixels[i] *= k;
  return img;
}

sb::FlipOptions hdr() {
  sb::FlipOptions o;
  o.input = sb::FlipInput::Hdr;
  return o;
}

void expectInUnitInterval(const sb::FlipResult& r, const std::string& what) {
  ASSERT_EQ(r.map.size(), static_cast<std::size_t>(r.width) * r.height) << what;
  for (std::size_t i = 0; i < r.map.size(); ++i) {
    ASSERT_GE(r.map[i], 0.0f) << what << " pixel " << i;
    ASSERT_LE(r.map[i], 1.0f) << what << " pixel " << i;
  }
  for (double v : {r.mean, r.weightedMedian, r.weightedQ1, r.weightedQ3, r.min, r.max}) {
    EXPECT_GE(v, 0.0) << what;
    EXPECT_LE(v, 1.0) << what;
  }
}

std::string dataFile(const std::string& name) {
  return (fs::path(SB_SOURCE_DIR) / "tests" / "data" / "flip" / name).string();
}

}  // namespace

// ------------------------------------------------------------------ stages

TEST(FlipStages, ColourSpaces) {
  using namespace sb::flip;
  const auto white = xyzToLab(linearRgbToXyz({1, 1, 1}));
  EXPECT_NEAR(white[0], 100.0f, 1e-3f);
  EXPECT_NEAR(white[1], 0.0f, 1e-3f);
  EXPECT_NEAR(white[2], 0.0f, 1e-3f);
  const auto black = xyzToLab(linearRgbToXyz({0, 0, 0}));
  EXPECT_NEAR(black[0], 0.0f, 1e-4f);
  // YyCxCz is invertible and linear in XYZ; linear RGB <-> XYZ round trips.
  const std::array<float, 3> rgb = {0.2f, 0.5f, 0.8f};
  const auto back = xyzToLinearRgb(ycxczToXyz(xyzToYcxcz(linearRgbToXyz(rgb))));
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(back[c], rgb[c], 1e-5f);
  EXPECT_NEAR(xyzToYcxcz(linearRgbToXyz({1, 1, 1}))[0], 100.0f, 1e-3f);
  EXPECT_FLOAT_EQ(srgbToLinear(0.0f), 0.0f);
  EXPECT_NEAR(srgbToLinear(1.0f), 1.0f, 1e-6f);
  EXPECT_NEAR(srgbToLinear(0.5f), 0.214041f, 1e-5f);
  // Hunt: chroma scaled by 0.01 L; HyAB: city block in L, Euclidean in (a, b).
  const auto h = huntAdjust({50, 20, -10});
  EXPECT_FLOAT_EQ(h[1], 10.0f);
  EXPECT_FLOAT_EQ(h[2], -5.0f);
  EXPECT_FLOAT_EQ(hyab({10, 0, 0}, {7, 3, 4}), 8.0f);
}

TEST(FlipStages, RedistributionMapsGreenBlueToOne) {
  using namespace sb::flip;
  EXPECT_EQ(redistributeColorError(0.0f), 0.0f);
  const auto huntLab = [](float r, float g, float b) {
    return huntAdjust(xyzToLab(linearRgbToXyz({r, g, b})));
  };
  const float greenBlue = hyab(huntLab(0, 1, 0), huntLab(0, 0, 1));
  EXPECT_NEAR(redistributeColorError(greenBlue), 1.0f, 1e-6f);
  // Black against white: a large difference, below green against blue.
  const float blackWhite = redistributeColorError(hyab(huntLab(0, 0, 0), huntLab(1, 1, 1)));
  EXPECT_GT(blackWhite, 0.9f);
  EXPECT_LT(blackWhite, 1.0f);
  // Monotonic in the distance.
  float previous = 0.0f;
  for (float d = 1.0f; d <= greenBlue; d += 1.0f) {
    const float e = redistributeColorError(d);
    EXPECT_GT(e, previous) << d;
    previous = e;
  }
}

TEST(FlipStages, FiltersAtSixtySevenPixelsPerDegree) {
  using namespace sb::flip;
  const ContrastSensitivityFilters csf = contrastSensitivityFilters(67.0);
  EXPECT_EQ(csf.radius, 10);  // 3 sigma of the widest Gaussian, b = 0.04: 9.05 pixels
  const auto sum = [](const std::vector<float>& v) {
    double s = 0;
    for (float x : v) s += x;
    return s;
  };
  EXPECT_NEAR(sum(csf.a), 1.0, 1e-6);
  EXPECT_NEAR(sum(csf.rg), 1.0, 1e-6);
  EXPECT_NEAR(sum(csf.by1) * sum(csf.by1) + sum(csf.by2) * sum(csf.by2), 1.0, 1e-6);
  const FeatureFilters f = featureFilters(67.0);
  EXPECT_EQ(f.radius, 9);  // 3 sigma, sigma = 0.5 * 0.082 * 67 = 2.75 pixels
  EXPECT_NEAR(sum(f.g), 1.0, 1e-6);
  EXPECT_NEAR(sum(f.dg), 0.0, 1e-6);
  EXPECT_NEAR(sum(f.ddg), 0.0, 1e-6);
  double positive = 0;
  for (float v : f.ddg) positive += std::max(v, 0.0f);
  EXPECT_NEAR(positive, 1.0, 1e-6);
  // Fewer pixels per degree: narrower filters.
  EXPECT_LT(contrastSensitivityFilters(30.0).radius, csf.radius);
  EXPECT_LT(featureFilters(30.0).radius, f.radius);
}

TEST(FlipStages, ExposureRangeFromTheReference) {
  using namespace sb::flip;
  EXPECT_EQ(toneMap(0.0f), 0.0f);
  Planes p(4, 4);
  for (auto& c : p.c) std::fill(c.begin(), c.end(), 0.5f);
  ExposureRange e = exposureRange(p);
  EXPECT_NEAR(e.start, e.stop, 1e-9);  // uniform: Ymax = Ymedian
  EXPECT_EQ(e.count, 2);
  // The start exposure takes the brightest pixel to 0.85 after tone mapping.
  const float x = 0.5f * static_cast<float>(std::exp2(e.start));
  EXPECT_NEAR(toneMap(x), 0.85f, 1e-5f);
  // Mostly black: the median of the lit pixels (the plain median, 0, has no stop).
  Planes dark(4, 4);
  for (int c = 0; c < 3; ++c) {
    dark.c[c][0] = 4.0f;
    dark.c[c][1] = 1.0f;
    dark.c[c][2] = 0.25f;
  }
  e = exposureRange(dark);
  EXPECT_NEAR(e.stop - e.start, 2.0, 1e-6);  // log2(4 / 1)
  EXPECT_EQ(e.count, 2);
  Planes black(4, 4);
  e = exposureRange(black);
  EXPECT_EQ(e.start, 0.0);
  EXPECT_EQ(e.stop, 0.0);
}

TEST(FlipStages, WeightedPercentilesAsNvidiasTool) {
  EXPECT_FLOAT_EQ(sb::flipWeightedPercentile({0.4f, 0.1f, 0.3f, 0.2f}, 0.25), 0.2f);
  EXPECT_FLOAT_EQ(sb::flipWeightedPercentile({0.4f, 0.1f, 0.3f, 0.2f}, 0.5), 0.3f);
  EXPECT_FLOAT_EQ(sb::flipWeightedPercentile({0.4f, 0.1f, 0.3f, 0.2f}, 0.75), 0.4f);
  EXPECT_EQ(sb::flipWeightedPercentile({0.0f, 0.0f}, 0.5), 0.0);
  EXPECT_EQ(sb::flipWeightedPercentile({}, 0.5), 0.0);
}

TEST(FlipStages, MagmaEnds) {
  const auto lo = sb::magma(0.0), hi = sb::magma(1.0), nan = sb::magma(std::nan(""));
  EXPECT_FLOAT_EQ(lo[0], 0.001462f);
  EXPECT_FLOAT_EQ(hi[2], 0.749504f);
  EXPECT_EQ(nan, lo);
  EXPECT_EQ(sb::magma(2.0), hi);
  // Brighter with the error (the map reads from black to pale yellow).
  double previous = -1;
  for (double t = 0; t <= 1.0; t += 0.05) {
    const auto c = sb::magma(t);
    const double lum = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    EXPECT_GT(lum, previous) << t;
    previous = lum;
  }
}

// ------------------------------------------------------------------ properties

TEST(Flip, IdenticalImagesGiveZeroEverywhere) {
  const sb::Image a = StrandPicture{}.image();
  for (const auto& [what, r] :
       {std::pair{"ldr", sb::computeFlip(a, a)},
        std::pair{"hdr", sb::computeFlip(scaled(a, 8.0f), scaled(a, 8.0f), hdr())}}) {
    for (float v : r.map) ASSERT_EQ(v, 0.0f) << what;
    EXPECT_EQ(r.mean, 0.0) << what;
    EXPECT_EQ(r.max, 0.0) << what;
    EXPECT_EQ(r.weightedMedian, 0.0) << what;
    EXPECT_EQ(r.weightedQ1, 0.0) << what;
    EXPECT_EQ(r.weightedQ3, 0.0) << what;
  }
}

TEST(Flip, EveryValueIsInZeroToOne) {
  const int n = 48;
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  sb::Image noiseA(n, n), noiseB(n, n), black(n, n, 4, 0.0f), white(n, n, 4, 1.0f);
  for (float& v : noiseA.pixels) v = u(rng);
  for (float& v : noiseB.pixels) v = u(rng);
  sb::Image green(n, n, 4, 0.0f), blue(n, n, 4, 0.0f), checker(n, n, 4, 0.0f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      green.at(x, y, 1) = 1.0f;
      blue.at(x, y, 2) = 1.0f;
      for (int c = 0; c < 3; ++c) checker.at(x, y, c) = ((x + y) % 2) ? 1.0f : 0.0f;
    }
  sb::Image outOfRange = noiseA;  // an LDR input is clamped, infinities included
  outOfRange.at(3, 3, 0) = std::numeric_limits<float>::infinity();
  outOfRange.at(4, 4, 1) = -5.0f;
  outOfRange.at(5, 5, 2) = 7.0f;
  const sb::Image strands = StrandPicture{}.image();
  expectInUnitInterval(sb::computeFlip(noiseA, noiseB), "noise");
  expectInUnitInterval(sb::computeFlip(black, white), "black/white");
  expectInUnitInterval(sb::computeFlip(checker, white), "checker/white");
  expectInUnitInterval(sb::computeFlip(outOfRange, noiseB), "out of range");
  expectInUnitInterval(sb::computeFlip(strands, withoutFirst(12).image()), "strands");
  expectInUnitInterval(sb::computeFlip(scaled(noiseA, 1e4f), noiseB, hdr()), "hdr noise");
  expectInUnitInterval(sb::computeFlip(scaled(strands, 50.0f), strands, hdr()), "hdr strands");
  expectInUnitInterval(sb::computeFlip(black, scaled(noiseB, 3.0f), hdr()), "hdr black");
  sb::Image huge = noiseA;  // finite, but its square is not
  huge.at(2, 2, 0) = 1e30f;
  huge.at(3, 2, 1) = -1e30f;
  expectInUnitInterval(sb::computeFlip(huge, noiseB, hdr()), "hdr huge");
  expectInUnitInterval(sb::computeFlip(noiseB, huge, hdr()), "hdr huge reference");
  // Green against blue is the largest difference: 1 everywhere.
  const sb::FlipResult gb = sb::computeFlip(green, blue);
  expectInUnitInterval(gb, "green/blue");
  EXPECT_NEAR(gb.min, 1.0, 1e-5);
}

TEST(Flip, MoreStrandsRemovedNeverScoresLower) {
  const sb::Image reference = withoutFirst(0).image();
  double previous = 0.0;
  std::ostringstream measured;
  for (int removed : {1, 2, 4, 8, 16, 24}) {
    const double mean = sb::computeFlip(withoutFirst(removed).image(), reference).mean;
    measured << " " << removed << ": " << mean;
    EXPECT_GT(mean, previous) << removed << " strands removed;" << measured.str();
    previous = mean;
  }
  std::cout << "[ measured ] mean FLIP by strands removed (of 24):" << measured.str() << "\n";
}

TEST(Flip, LargerShiftNeverScoresLower) {
  // Few strands, so that a shift does not move one onto another's place.
  StrandPicture p;
  p.strands = 6;
  const sb::Image reference = p.image();
  double previous = 0.0;
  std::ostringstream measured;
  for (double shift : {0.25, 0.5, 1.0, 2.0, 3.0, 4.0}) {
    p.shift = shift;
    const double mean = sb::computeFlip(p.image(), reference).mean;
    measured << " " << shift << ": " << mean;
    EXPECT_GT(mean, previous) << "shift " << shift << ";" << measured.str();
    previous = mean;
  }
  std::cout << "[ measured ] mean FLIP by shift (pixels):" << measured.str() << "\n";
}

TEST(Flip, MissingStrandHasTheHighestErrors) {
  StrandPicture full;
  const sb::Image reference = full.image();
  const int missing = 7;
  StrandPicture without = full;
  without.drawn.assign(static_cast<std::size_t>(full.strands), true);
  without.drawn[missing] = false;
  const sb::FlipResult r = sb::computeFlip(without.image(), reference);

  // The strand's own pixels: those it covers by at least half.
  const auto strand = full.layout()[missing];
  std::vector<float> onStrand;
  for (int y = 0; y < full.height; ++y)
    for (int x = 0; x < full.width; ++x)
      if (full.coverage(strand, x, y) >= 0.5)
        onStrand.push_back(r.map[static_cast<std::size_t>(y) * full.width + x]);
  ASSERT_GE(onStrand.size(), static_cast<std::size_t>(full.height));
  std::vector<float> sorted = r.map;
  std::sort(sorted.begin(), sorted.end());
  const auto percentile = [&](double p) {
    return sorted[static_cast<std::size_t>(p * (sorted.size() - 1))];
  };
  std::sort(onStrand.begin(), onStrand.end());
  const float strandMedian = onStrand[onStrand.size() / 2];
  std::cout << "[ measured ] missing strand: " << onStrand.size() << " pixels, their median FLIP "
            << strandMedian << ", lowest " << onStrand.front() << "; map max " << r.max
            << ", 99th percentile " << percentile(0.99) << ", 97th " << percentile(0.97) << "\n";
  // The strand covers ~1 % of the image: its typical pixel is in the map's top
  // 1 % and its lowest in the top 3 %, and the map's maximum is on it.
  EXPECT_GE(strandMedian, percentile(0.99));
  EXPECT_GE(onStrand.front(), percentile(0.97));
  EXPECT_EQ(onStrand.back(), static_cast<float>(r.max));
}

TEST(Flip, NanPixelsAreTheLargestError) {
  const sb::Image reference = StrandPicture{}.image();
  sb::Image test = reference;
  test.at(40, 50, 1) = std::numeric_limits<float>::quiet_NaN();
  const sb::FlipResult r = sb::computeFlip(test, reference);
  EXPECT_EQ(r.nanPixels, 1);
  EXPECT_EQ(r.map[50 * 128 + 40], 1.0f);
  EXPECT_GT(r.mean, 0.0);
  expectInUnitInterval(r, "nan");
  // HDR: an infinite sample too, on either side.
  sb::Image inf = scaled(reference, 4.0f);
  inf.at(10, 10, 0) = std::numeric_limits<float>::infinity();
  const sb::FlipResult h = sb::computeFlip(scaled(reference, 4.0f), inf, hdr());
  EXPECT_EQ(h.nanPixels, 1);
  EXPECT_EQ(h.map[10 * 128 + 10], 1.0f);
  expectInUnitInterval(h, "hdr inf");
  const nlohmann::json j = sb::toJson(h);
  EXPECT_EQ(j["nan_pixels"], 1);
  EXPECT_NO_THROW(nlohmann::json::parse(j.dump()));
}

TEST(Flip, RefusesMismatchedImages) {
  EXPECT_THROW(sb::computeFlip(sb::Image(4, 4), sb::Image(5, 4)), sb::InputError);
  EXPECT_THROW(sb::computeFlip(sb::Image(4, 4, 1), sb::Image(4, 4, 1)), sb::InputError);
  sb::FlipOptions bad;
  bad.ppd = 0.0;
  EXPECT_THROW(sb::computeFlip(sb::Image(4, 4), sb::Image(4, 4), bad), std::invalid_argument);
  bad.ppd = 1e9;  // filters of a billion taps
  EXPECT_THROW(sb::computeFlip(sb::Image(4, 4), sb::Image(4, 4), bad), std::invalid_argument);
  const sb::FlipResult empty = sb::computeFlip(sb::Image(0, 0), sb::Image(0, 0));
  EXPECT_TRUE(empty.map.empty());
}

// Images smaller than the filters, and the extremes of the ppd range.
TEST(Flip, TinyImagesAndExtremePixelsPerDegree) {
  const sb::Image pic = StrandPicture{}.image();
  sb::Image other = withoutFirst(6).image();
  for (const auto& [w, h] : {std::pair{1, 1}, std::pair{3, 2}, std::pair{2, 17}}) {
    sb::Image a(w, h), b(w, h);
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        for (int c = 0; c < 4; ++c) {
          a.at(x, y, c) = pic.at(x + 20, y, c);
          b.at(x, y, c) = 1.0f - pic.at(x + 20, y, c);
        }
    expectInUnitInterval(sb::computeFlip(a, b), std::to_string(w) + "x" + std::to_string(h));
    expectInUnitInterval(sb::computeFlip(a, b, hdr()), "hdr " + std::to_string(w));
  }
  for (double ppd : {0.01, 1.0, 1000.0}) {
    sb::FlipOptions o;
    o.ppd = ppd;
    const sb::FlipResult r = sb::computeFlip(other, pic, o);
    expectInUnitInterval(r, "ppd " + std::to_string(ppd));
    EXPECT_GT(r.mean, 0.0) << ppd;
  }
}

// ------------------------------------------------------------------ the reference implementation

// A committed rendered pair (64x64, written by strandbench render):
//   strandbench render --scene straight:strands=2000 --shadow osm:maps=4 --size 64x64 --fov 12
//       --out osm4.{png,exr}
//   strandbench render --scene straight:strands=2000 --shadow exact --size 64x64 --fov 12
//       --out exact.{png,exr}
// and the numbers NVIDIA's FLIP tool prints for it: FLIP v1.6 (the C++ tool of
// github.com/NVlabs/flip at commit 1eb247c, built with g++ -O2 -fopenmp), run as
//   flip -r exact.png -t osm4.png -ppd 67    (LDR-FLIP)
//   flip -r exact.exr -t osm4.exr -ppd 67    (HDR-FLIP, exposures from the reference)
struct ReferenceNumbers {
  const char* ext;
  double mean, weightedMedian, weightedQ1, weightedQ3, max;
  double startExposure, stopExposure;
  int exposures;
};
constexpr ReferenceNumbers kNvidiaFlip[] = {
    {"png", 0.179332, 0.299373, 0.204952, 0.405736, 0.696202, 0, 0, 0},
    {"exr", 0.148048, 0.249053, 0.150690, 0.326534, 0.534784, 1.3899, 3.2638, 2},
};

TEST(Flip, AgreesWithNvidiasReferenceImplementation) {
  for (const ReferenceNumbers& ref : kNvidiaFlip) {
    const std::string ext = ref.ext;
    sb::FlipOptions o;
    o.input = ext == "exr" ? sb::FlipInput::Hdr : sb::FlipInput::Ldr;
    const sb::FlipResult r = sb::computeFlip(sb::readImage(dataFile("osm4." + ext)),
                                             sb::readImage(dataFile("exact." + ext)), o);
    std::cout << "[ measured ] " << ext << ": mean " << r.mean << " (NVIDIA " << ref.mean
              << "), weighted median " << r.weightedMedian << " (" << ref.weightedMedian << ")\n";
    // Required: 0.001 in the mean. The tool prints 6 decimals.
    EXPECT_NEAR(r.mean, ref.mean, 1e-5) << ext;
    EXPECT_NEAR(r.weightedMedian, ref.weightedMedian, 1e-4) << ext;
    EXPECT_NEAR(r.weightedQ1, ref.weightedQ1, 1e-4) << ext;
    EXPECT_NEAR(r.weightedQ3, ref.weightedQ3, 1e-4) << ext;
    EXPECT_NEAR(r.max, ref.max, 1e-5) << ext;
    if (o.input == sb::FlipInput::Hdr) {
      EXPECT_NEAR(r.startExposure, ref.startExposure, 1e-4);
      EXPECT_NEAR(r.stopExposure, ref.stopExposure, 1e-4);
      EXPECT_EQ(r.exposures, ref.exposures);
    }
  }
}

// ------------------------------------------------------------------ compare

class FlipCompareTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sb_test_flip_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  nlohmann::json compare(const std::string& a, const std::string& b, double ppd,
                         const std::string& map = "") {
    std::ostringstream out, err;
    EXPECT_EQ(sb::runCompareCommand(a, b, out, err, 1.0 / 255.0, ppd, map), 0) << err.str();
    return nlohmann::json::parse(out.str());
  }
  fs::path dir_;
};

TEST_F(FlipCompareTest, JsonHasFlipAndTheMapIsWritten) {
  sb::writeImage(withoutFirst(3).image(), file("a.png"));
  sb::writeImage(withoutFirst(0).image(), file("b.png"));
  const nlohmann::json j = compare(file("a.png"), file("b.png"), 67.0, file("map.png"));
  ASSERT_TRUE(j.contains("flip")) << j.dump();
  for (const char* k : {"mean", "weighted_median", "weighted_q1", "weighted_q3", "min", "max",
                        "nan_pixels", "ppd", "input"})
    EXPECT_TRUE(j["flip"].contains(k)) << k;
  EXPECT_EQ(j["flip"]["input"], "ldr");
  EXPECT_EQ(j["flip"]["ppd"], 67.0);
  const double mean = j["flip"]["mean"].get<double>();
  EXPECT_GT(mean, 0.0);
  EXPECT_LE(j["flip"]["weighted_q1"].get<double>(), j["flip"]["weighted_median"].get<double>());
  EXPECT_LE(j["flip"]["weighted_median"].get<double>(), j["flip"]["weighted_q3"].get<double>());
  // The map: magma of the error, the same size; black where nothing differs.
  const sb::Image map = sb::readImage(file("map.png"));
  EXPECT_EQ(map.width, 128);
  EXPECT_NEAR(map.at(0, 0, 0), sb::magma(0.0)[0], 1.0 / 255.0);
  // Another viewing distance: fewer pixels per degree.
  const nlohmann::json far = compare(file("a.png"), file("b.png"), 20.0);
  EXPECT_EQ(far["flip"]["ppd"], 20.0);
  EXPECT_NE(far["flip"]["mean"].get<double>(), mean);
  // Identical files: 0.
  EXPECT_EQ(compare(file("b.png"), file("b.png"), 67.0)["flip"]["mean"], 0.0);
}

TEST_F(FlipCompareTest, ExrIsHdrFlip) {
  sb::writeImage(scaled(withoutFirst(3).image(), 5.0f), file("a.exr"));
  sb::writeImage(scaled(withoutFirst(0).image(), 5.0f), file("b.exr"));
  const nlohmann::json j = compare(file("a.exr"), file("b.exr"), 67.0);
  EXPECT_EQ(j["flip"]["input"], "hdr");
  ASSERT_TRUE(j["flip"].contains("exposures")) << j.dump();
  EXPECT_GE(j["flip"]["exposures"]["count"].get<int>(), 2);
  EXPECT_LT(j["flip"]["exposures"]["start"].get<double>(),
            j["flip"]["exposures"]["stop"].get<double>());
  EXPECT_GT(j["flip"]["mean"].get<double>(), 0.0);
}

// The cost that `render --reference` adds per image: a 512x512 pair.
TEST(Flip, TimeOfA512Pair) {
  StrandPicture p;
  p.width = p.height = 512;
  p.strands = 200;
  const sb::Image reference = p.image();
  p.shift = 1.0;
  const sb::Image test = p.image();
  const auto t0 = std::chrono::steady_clock::now();
  const sb::FlipResult r = sb::computeFlip(test, reference);
  const double ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "[ measured ] LDR-FLIP of a 512x512 pair: " << ms << " ms (mean " << r.mean << ")\n";
  EXPECT_GT(r.mean, 0.0);
}
