#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>

#include "imaging/image.h"
#include "imaging/metrics.h"
#include "scenes/scene.h"

namespace fs = std::filesystem;

namespace {

sb::Image pattern(int w, int h) {
  sb::Image img(w, h, 4);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 4; ++c) {
        img.at(x, y, c) = static_cast<float>((x * 3 + y * 5 + c * 11) % 17) / 20.0f;
      }
    }
  }
  return img;
}

constexpr double kInf = std::numeric_limits<double>::infinity();

}  // namespace

TEST(Metrics, IdenticalImages) {
  const sb::Image a = pattern(10, 10);
  const sb::ImageError e = sb::compareImages(a, a);
  EXPECT_EQ(e.rmse, 0.0);
  EXPECT_EQ(e.psnr, kInf);
  EXPECT_EQ(e.maxAbs, 0.0);
  EXPECT_EQ(e.fractionOver, 0.0);
  EXPECT_EQ(e.nanPixels, 0);
  EXPECT_EQ(e.width, 10);
  EXPECT_EQ(e.height, 10);
  EXPECT_TRUE(e.identical());

  const nlohmann::json j = sb::toJson(e);
  EXPECT_TRUE(j["psnr"].is_null());
  EXPECT_EQ(j["identical"], true);
  EXPECT_EQ(j["rmse"], 0.0);
  EXPECT_EQ(j["max_abs"], 0.0);
  EXPECT_EQ(j["nan_pixels"], 0);
  // Valid JSON text (no inf / nan tokens).
  EXPECT_NO_THROW(nlohmann::json::parse(j.dump()));
}

TEST(Metrics, ConstantOffsetOnRgb) {
  const sb::Image a = pattern(8, 6);
  sb::Image b = a;
  for (int y = 0; y < b.height; ++y) {
    for (int x = 0; x < b.width; ++x) {
      for (int c = 0; c < 3; ++c) b.at(x, y, c) += 0.1f;
      b.at(x, y, 3) = 0.0f;  // alpha differs wildly but is not compared
    }
  }
  const sb::ImageError e = sb::compareImages(a, b);
  EXPECT_NEAR(e.rmse, 0.1, 1e-6);
  EXPECT_NEAR(e.psnr, 20.0, 1e-4);
  EXPECT_NEAR(e.maxAbs, 0.1, 1e-6);
  EXPECT_EQ(e.fractionOver, 1.0);
  EXPECT_EQ(e.pixelsOver, 48);
  EXPECT_FALSE(e.identical());

  // Including alpha (4 channels) sees the alpha change.
  EXPECT_GT(sb::compareImages(a, b, 1.0 / 255.0, 4).maxAbs, 0.1 + 1e-6);
}

TEST(Metrics, SingleChangedPixel) {
  const sb::Image a(10, 10, 4, 0.25f);
  sb::Image b = a;
  for (int c = 0; c < 3; ++c) b.at(3, 7, c) = 0.75f;  // +0.5 exactly
  const sb::ImageError e = sb::compareImages(a, b);
  // 3 samples of 0.5 among 300: rmse = sqrt(3 * 0.25 / 300) = 0.05.
  EXPECT_DOUBLE_EQ(e.rmse, std::sqrt(3 * 0.25 / 300.0));
  EXPECT_DOUBLE_EQ(e.rmse, 0.05);
  EXPECT_NEAR(e.psnr, 20.0 * std::log10(20.0), 1e-9);  // 26.0206 dB
  EXPECT_DOUBLE_EQ(e.maxAbs, 0.5);
  EXPECT_DOUBLE_EQ(e.fractionOver, 0.01);
  EXPECT_EQ(e.pixelsOver, 1);
}

TEST(Metrics, ValuesAreNotClamped) {
  const sb::Image a(2, 2, 4, 1.0f);
  const sb::Image b(2, 2, 4, 3.0f);
  const sb::ImageError e = sb::compareImages(a, b);
  EXPECT_DOUBLE_EQ(e.maxAbs, 2.0);
  EXPECT_DOUBLE_EQ(e.rmse, 2.0);
  EXPECT_NEAR(e.psnr, -20.0 * std::log10(2.0), 1e-12);
}

TEST(Metrics, ThresholdIsOneCodeOfEightBit) {
  sb::Image a(3, 1, 4, 0.0f);
  sb::Image b = a;
  for (int c = 0; c < 3; ++c) {
    a.at(0, 0, c) = 200.0f / 255.0f;  // one code apart: not over
    b.at(0, 0, c) = 201.0f / 255.0f;
    a.at(1, 0, c) = 254.0f / 255.0f;  // one code apart near 1: not over
    b.at(1, 0, c) = 255.0f / 255.0f;
    a.at(2, 0, c) = 10.0f / 255.0f;  // two codes apart: over
    b.at(2, 0, c) = 12.0f / 255.0f;
  }
  const sb::ImageError e = sb::compareImages(a, b);
  EXPECT_EQ(e.pixelsOver, 1);
  EXPECT_NEAR(e.fractionOver, 1.0 / 3.0, 1e-12);
  // Threshold 0 counts any difference.
  EXPECT_EQ(sb::compareImages(a, b, 0.0).pixelsOver, 3);
}

TEST(Metrics, SizeMismatchThrowsWithBothSizes) {
  try {
    sb::compareImages(sb::Image(10, 10), sb::Image(10, 12));
    FAIL() << "expected InputError";
  } catch (const sb::InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("10x10"), std::string::npos) << msg;
    EXPECT_NE(msg.find("10x12"), std::string::npos) << msg;
  }
  EXPECT_THROW(sb::diffHeatmap(sb::Image(4, 4), sb::Image(5, 4), 1.0), sb::InputError);
}

TEST(Metrics, TooFewChannelsThrows) {
  EXPECT_THROW(sb::compareImages(sb::Image(2, 2, 1), sb::Image(2, 2, 4)), sb::InputError);
  EXPECT_THROW(sb::compareImages(sb::Image(2, 2), sb::Image(2, 2), 0.1, 0), std::invalid_argument);
}

TEST(Metrics, NanPixelIsReportedNotHidden) {
  const sb::Image a(10, 10, 4, 0.5f);
  sb::Image b = a;
  b.at(4, 4, 1) = std::numeric_limits<float>::quiet_NaN();
  const sb::ImageError e = sb::compareImages(a, b);
  EXPECT_EQ(e.nanPixels, 1);
  EXPECT_EQ(e.pixelsOver, 1);
  EXPECT_DOUBLE_EQ(e.fractionOver, 0.01);
  EXPECT_EQ(e.maxAbs, kInf);
  EXPECT_EQ(e.rmse, kInf);
  EXPECT_EQ(e.psnr, -kInf);
  EXPECT_FALSE(e.identical());

  // NaN in both images at the same place is still a NaN difference.
  const sb::ImageError both = sb::compareImages(b, b);
  EXPECT_EQ(both.nanPixels, 1);
  EXPECT_FALSE(both.identical());

  const nlohmann::json j = sb::toJson(e);
  EXPECT_EQ(j["nan_pixels"], 1);
  EXPECT_EQ(j["identical"], false);
  EXPECT_TRUE(j["rmse"].is_null());
  EXPECT_TRUE(j["psnr"].is_null());
  EXPECT_TRUE(j["max_abs"].is_null());
  EXPECT_NO_THROW(nlohmann::json::parse(j.dump()));

  // NaN in alpha is not compared by default.
  sb::Image c = a;
  c.at(0, 0, 3) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(sb::compareImages(a, c).nanPixels, 0);
  EXPECT_EQ(sb::compareImages(a, c, 1.0 / 255.0, 4).nanPixels, 1);
}

TEST(Metrics, ViridisEndpointsAndOrder) {
  const auto lo = sb::viridis(0.0);
  const auto hi = sb::viridis(1.0);
  EXPECT_FLOAT_EQ(lo[0], 0.267004f);
  EXPECT_FLOAT_EQ(lo[1], 0.004874f);
  EXPECT_FLOAT_EQ(lo[2], 0.329415f);
  EXPECT_FLOAT_EQ(hi[0], 0.993248f);
  EXPECT_FLOAT_EQ(hi[1], 0.906157f);
  EXPECT_FLOAT_EQ(hi[2], 0.143936f);
  EXPECT_EQ(sb::viridis(-1.0), lo);
  EXPECT_EQ(sb::viridis(7.0), hi);
  // Matplotlib's viridis at entry 128 (t = 128/255): (0.128729, 0.563265, 0.551229).
  const auto mid = sb::viridis(128.0 / 255.0);
  EXPECT_NEAR(mid[0], 0.128729, 0.01);
  EXPECT_NEAR(mid[1], 0.563265, 0.01);
  EXPECT_NEAR(mid[2], 0.551229, 0.01);
  // Green rises monotonically (viridis' lightness is monotonic).
  float prev = -1.0f;
  for (int i = 0; i <= 100; ++i) {
    const float g = sb::viridis(i / 100.0)[1];
    EXPECT_GT(g, prev);
    prev = g;
  }
}

TEST(Metrics, HeatmapEndpoints) {
  const sb::Image a(4, 3, 4, 0.2f);
  sb::Image b = a;
  b.at(1, 1, 0) = 0.6f;                                     // diff 0.4 = scale -> top
  b.at(2, 1, 2) = 0.4f;                                     // diff 0.2 = half scale
  b.at(3, 2, 1) = 1.2f;                                     // diff 1.0 > scale -> top
  b.at(0, 2, 0) = std::numeric_limits<float>::quiet_NaN();  // NaN -> magenta
  const sb::Image h = sb::diffHeatmap(a, b, 0.4);
  ASSERT_EQ(h.width, 4);
  ASSERT_EQ(h.height, 3);
  ASSERT_EQ(h.channels, 4);
  const auto lo = sb::viridis(0.0), hi = sb::viridis(1.0), half = sb::viridis(0.5);
  for (int c = 0; c < 3; ++c) {
    EXPECT_EQ(h.at(0, 0, c), lo[c]);  // no difference
    EXPECT_EQ(h.at(1, 1, c), hi[c]);
    EXPECT_NEAR(h.at(2, 1, c), half[c], 1e-5);
    EXPECT_EQ(h.at(3, 2, c), hi[c]);
  }
  EXPECT_EQ(h.at(0, 2, 0), 1.0f);
  EXPECT_EQ(h.at(0, 2, 1), 0.0f);
  EXPECT_EQ(h.at(0, 2, 2), 1.0f);
  for (int y = 0; y < 3; ++y) {
    for (int x = 0; x < 4; ++x) EXPECT_EQ(h.at(x, y, 3), 1.0f);
  }
  EXPECT_THROW(sb::diffHeatmap(a, b, 0.0), std::invalid_argument);
}

// --------------------------------------------------------------------- SSIM

// SSIM of two flat images a and b: the variances and the covariance are 0, so
// only the luminance term is left: (2ab + C1) / (a^2 + b^2 + C1), C1 = 0.01^2.
double flatSsim(double a, double b) {
  const double c1 = 0.01 * 0.01;
  return (2.0 * a * b + c1) / (a * a + b * b + c1);
}

TEST(Ssim, IdenticalImagesGiveExactlyOne) {
  const sb::Image a = pattern(20, 17);
  EXPECT_EQ(sb::compareImages(a, a).ssim, 1.0);
  EXPECT_EQ(sb::compareImages(a, a, 0.0, 4).ssim, 1.0);
  EXPECT_EQ(sb::toJson(sb::compareImages(a, a))["ssim"], 1.0);
  // Smaller than the 11x11 window: the largest odd window that fits.
  const sb::Image tiny = pattern(4, 6);
  EXPECT_EQ(sb::compareImages(tiny, tiny).ssim, 1.0);
}

TEST(Ssim, ConstantOffsetOnFlatImagesIsTheLuminanceTerm) {
  for (const auto& [a, b] : {std::pair{0.25f, 0.35f}, {0.0f, 0.1f}, {0.8f, 0.5f}}) {
    const sb::ImageError e =
        sb::compareImages(sb::Image(16, 16, 4, a), sb::Image(16, 16, 4, b), 1.0 / 255.0);
    EXPECT_NEAR(e.ssim, flatSsim(a, b), 1e-9) << a << " vs " << b;
    // A 5x5 image (window 5x5) gives the same value.
    EXPECT_NEAR(sb::compareImages(sb::Image(5, 5, 4, a), sb::Image(5, 5, 4, b)).ssim,
                flatSsim(a, b), 1e-9);
  }
  // 0.25 vs 0.35: (0.175 + 1e-4) / (0.185 + 1e-4).
  EXPECT_NEAR(flatSsim(0.25f, 0.35f), 0.1751 / 0.1851, 1e-7);
}

TEST(Ssim, MatchesADirectTwoDimensionalComputation) {
  // Reference value from a direct (non-separable) evaluation of Wang et al.'s
  // formula in Python, float32 inputs, double arithmetic: a pattern against
  // itself shifted left by one pixel (wrapping), 16x14, RGB.
  const sb::Image a = pattern(16, 14);
  sb::Image b = a;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x)
      for (int c = 0; c < 4; ++c) b.at(x, y, c) = a.at((x + 1) % a.width, y, c);
  EXPECT_NEAR(sb::compareImages(a, b).ssim, 0.12940303084244445, 1e-9);
}

TEST(Ssim, OneChangedPixelIsBelowOne) {
  const sb::Image a(20, 20, 4, 0.25f);
  sb::Image b = a;
  b.at(9, 9, 1) = 0.3f;
  const double s = sb::compareImages(a, b).ssim;
  EXPECT_LT(s, 1.0);
  EXPECT_GT(s, 0.9);
  // A change in alpha is not compared by default.
  sb::Image c = a;
  c.at(9, 9, 3) = 0.0f;
  EXPECT_EQ(sb::compareImages(a, c).ssim, 1.0);
  EXPECT_LT(sb::compareImages(a, c, 0.0, 4).ssim, 1.0);
}

TEST(Ssim, DecreasesWithNoise) {
  const sb::Image a = pattern(48, 40);
  double previous = 1.0;
  for (const double sigma : {0.005, 0.02, 0.05, 0.1, 0.3}) {
    std::mt19937 rng(42);
    std::normal_distribution<float> noise(0.0f, static_cast<float>(sigma));
    sb::Image b = a;
    for (float& v : b.pixels) v += noise(rng);
    const double s = sb::compareImages(a, b).ssim;
    EXPECT_LT(s, previous) << "sigma " << sigma;
    EXPECT_GT(s, -1.0);
    previous = s;
  }
  EXPECT_LT(previous, 0.7);  // 0.58 at sigma 0.3 (the pattern itself varies a lot)
}

TEST(Ssim, NonFiniteSampleGivesNullNotOne) {
  const sb::Image a(12, 12, 4, 0.5f);
  sb::Image b = a;
  b.at(3, 3, 0) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(std::isnan(sb::compareImages(a, b).ssim));
  EXPECT_TRUE(sb::toJson(sb::compareImages(a, b))["ssim"].is_null());
  b.at(3, 3, 0) = std::numeric_limits<float>::infinity();
  EXPECT_TRUE(std::isnan(sb::compareImages(a, b).ssim));
}

class CompareCommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sb_test_compare_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(CompareCommandTest, PrintsOneJsonObject) {
  const sb::Image a(10, 10, 4, 0.25f);
  sb::Image b = a;
  for (int c = 0; c < 3; ++c) b.at(3, 7, c) = 0.75f;
  sb::writeImage(a, file("a.exr"));
  sb::writeImage(b, file("b.exr"));
  std::ostringstream out, err;
  ASSERT_EQ(sb::runCompareCommand(file("a.exr"), file("b.exr"), out, err), 0) << err.str();
  EXPECT_EQ(err.str(), "");
  const nlohmann::json j = nlohmann::json::parse(out.str());
  for (const char* key : {"a", "b", "width", "height", "rmse", "psnr", "max_abs", "ssim",
                          "fraction_over", "nan_pixels", "identical"}) {
    EXPECT_TRUE(j.contains(key)) << key;
  }
  EXPECT_EQ(j["a"], file("a.exr"));
  EXPECT_EQ(j["b"], file("b.exr"));
  EXPECT_EQ(j["width"], 10);
  EXPECT_EQ(j["height"], 10);
  EXPECT_DOUBLE_EQ(j["rmse"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(j["max_abs"].get<double>(), 0.5);
  EXPECT_DOUBLE_EQ(j["fraction_over"].get<double>(), 0.01);
  EXPECT_EQ(j["nan_pixels"], 0);
  EXPECT_EQ(j["identical"], false);
  EXPECT_LT(j["ssim"].get<double>(), 1.0);

  std::ostringstream out2, err2;
  ASSERT_EQ(sb::runCompareCommand(file("a.exr"), file("a.exr"), out2, err2), 0);
  const nlohmann::json same = nlohmann::json::parse(out2.str());
  EXPECT_TRUE(same["psnr"].is_null());
  EXPECT_EQ(same["identical"], true);
  EXPECT_EQ(same["ssim"], 1.0);
}

TEST_F(CompareCommandTest, InputErrorsGiveStatus2) {
  sb::writeImage(sb::Image(4, 4, 4, 0.5f), file("small.png"));
  sb::writeImage(sb::Image(5, 4, 4, 0.5f), file("wide.png"));
  {
    std::ostringstream out, err;
    EXPECT_EQ(sb::runCompareCommand(file("small.png"), file("missing.png"), out, err), 2);
    EXPECT_EQ(out.str(), "");
    EXPECT_EQ(err.str().rfind("strandbench compare: ", 0), 0u) << err.str();
    EXPECT_NE(err.str().find(file("missing.png")), std::string::npos) << err.str();
  }
  {
    std::ostringstream out, err;
    EXPECT_EQ(sb::runCompareCommand(file("small.png"), file("wide.png"), out, err), 2);
    EXPECT_NE(err.str().find("4x4"), std::string::npos) << err.str();
    EXPECT_NE(err.str().find("5x4"), std::string::npos) << err.str();
  }
}

// The banding measure: the luminance error's RMSE after a (2r+1)^2 box filter.
TEST(Metrics, BandingKeepsCoherentErrorAndAveragesNoiseOut) {
  const int n = 32;
  sb::Image ref(n, n, 3, 0.5f), offset(n, n, 3, 0.7f), noise(n, n, 3, 0.5f), band(n, n, 3, 0.5f);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x)
      for (int c = 0; c < 3; ++c) {
        noise.at(x, y, c) = 0.5f + (((x + y) % 2) ? 0.2f : -0.2f);  // zero-mean checkerboard
        band.at(x, y, c) = x < n / 2 ? 0.7f : 0.5f;  // a stripe: half the image off by 0.2
      }
  EXPECT_EQ(sb::bandingMeasure(ref, ref), 0.0);
  // A uniform error of 0.2 on every channel: luminance 0.2 (the weights sum to 1), kept.
  EXPECT_NEAR(sb::bandingMeasure(offset, ref), 0.2, 1e-6);
  // The checkerboard's RMSE is 0.2 too, but a 3x3 box inside the image holds 5 of one sign
  // and 4 of the other: |mean| 0.2 / 9 on the 30 x 30 inner pixels; a box on an edge (2 x 3)
  // or a corner (2 x 2) holds as many of each: 0. RMS: 0.2 / 9 * sqrt(900 / 1024).
  EXPECT_NEAR(sb::bandingMeasure(noise, ref, 1), 0.2 / 9 * std::sqrt(900.0 / 1024.0), 1e-6);
  // The stripe keeps most of its error: only the columns within r of the edge are smoothed.
  EXPECT_GT(sb::bandingMeasure(band, ref, 1), 0.9 * 0.2 * std::sqrt(0.5));
  EXPECT_THROW(sb::bandingMeasure(ref, sb::Image(4, 4, 3)), sb::InputError);
}
