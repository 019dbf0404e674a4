#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "imaging/image.h"
#include "scenes/scene.h"

namespace fs = std::filesystem;

namespace {

class ImageIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("sb_test_image_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string file(const std::string& name) const { return (dir_ / name).string(); }
  // Names in the folder, to check that no temporary file is left behind.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_)) names.push_back(e.path().filename());
    return names;
  }
  fs::path dir_;
};

// A gradient with distinct values per pixel and channel, including 0 and 1.
sb::Image testPattern(int w, int h, int channels = 4) {
  sb::Image img(w, h, channels);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < channels; ++c) {
        const float v = static_cast<float>((x * 7 + y * 13 + c * 29) % 101) / 100.0f;
        img.at(x, y, c) = v;
      }
    }
  }
  return img;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

double maxAbsDiff(const sb::Image& a, const sb::Image& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  double m = 0.0;
  for (std::size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    m = std::max(m, std::fabs(static_cast<double>(a.pixels[i]) - b.pixels[i]));
  }
  return m;
}

}  // namespace

TEST(Image, AtIsRowMajorInterleaved) {
  sb::Image img(3, 2, 4);
  img.at(2, 1, 3) = 5.0f;
  EXPECT_EQ(img.pixels[(1 * 3 + 2) * 4 + 3], 5.0f);
  EXPECT_EQ(img.pixels.size(), 3u * 2u * 4u);
}

TEST(Image, FromRowsFlipsUNorm8) {
  // 2x3, 1 channel; readback row 0 is the bottom of the picture.
  const std::vector<std::uint8_t> bytes = {0,   51,    // bottom row
                                           102, 153,   // middle
                                           204, 255};  // top
  const sb::Image img = sb::imageFromRows(bytes, 2, 3, sb::PixelType::UNorm8, 1);
  ASSERT_EQ(img.width, 2);
  ASSERT_EQ(img.height, 3);
  ASSERT_EQ(img.channels, 1);
  // The bottom readback row becomes the last Image row.
  EXPECT_FLOAT_EQ(img.at(0, 2, 0), 0.0f);
  EXPECT_FLOAT_EQ(img.at(1, 2, 0), 0.2f);
  EXPECT_FLOAT_EQ(img.at(0, 1, 0), 0.4f);
  EXPECT_FLOAT_EQ(img.at(0, 0, 0), 0.8f);
  EXPECT_FLOAT_EQ(img.at(1, 0, 0), 1.0f);
}

TEST(Image, FromRowsFlipsFloat32) {
  const int w = 3, h = 2, ch = 4;
  std::vector<float> rows(static_cast<std::size_t>(w * h * ch));
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = static_cast<float>(i) * 0.5f;
  std::vector<std::uint8_t> bytes(rows.size() * sizeof(float));
  std::memcpy(bytes.data(), rows.data(), bytes.size());
  const sb::Image img = sb::imageFromRows(bytes, w, h, sb::PixelType::Float32, ch);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < ch; ++c) {
        EXPECT_EQ(img.at(x, y, c), rows[static_cast<std::size_t>(((h - 1 - y) * w + x) * ch + c)]);
      }
    }
  }
}

TEST(Image, FromRowsRejectsWrongByteCount) {
  const std::vector<std::uint8_t> bytes(7);
  EXPECT_THROW(sb::imageFromRows(bytes, 2, 1, sb::PixelType::UNorm8, 4), std::invalid_argument);
  EXPECT_THROW(sb::imageFromRows(bytes, 0, 1, sb::PixelType::UNorm8, 4), std::invalid_argument);
}

TEST_F(ImageIoTest, Png8RoundTripWithinOneCode) {
  const sb::Image img = testPattern(17, 9);
  const std::string path = file("a.png");
  sb::writeImage(img, path);
  const sb::Image back = sb::readImage(path);
  ASSERT_EQ(back.width, 17);
  ASSERT_EQ(back.height, 9);
  ASSERT_EQ(back.channels, 4);
  EXPECT_LE(maxAbsDiff(img, back), 0.5 / 255.0 + 1e-6);
  // Stored code is round(v * 255), alpha included and not premultiplied.
  for (std::size_t i = 0; i < img.pixels.size(); ++i) {
    ASSERT_FLOAT_EQ(back.pixels[i] * 255.0f, std::round(img.pixels[i] * 255.0f)) << i;
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"a.png"});
}

TEST_F(ImageIoTest, Png8ClampsAndRounds) {
  sb::Image img(4, 1, 3);
  const float values[4] = {-0.5f, 2.0f, 0.5f / 255.0f + 1e-4f, NAN};
  for (int x = 0; x < 4; ++x) {
    for (int c = 0; c < 3; ++c) img.at(x, 0, c) = values[x];
  }
  const std::string path = file("clamp.png");
  sb::writeImage(img, path);
  const sb::Image back = sb::readImage(path);
  EXPECT_EQ(back.at(0, 0, 0), 0.0f);
  EXPECT_EQ(back.at(1, 0, 0), 1.0f);
  EXPECT_FLOAT_EQ(back.at(2, 0, 0), 1.0f / 255.0f);
  EXPECT_EQ(back.at(3, 0, 0), 0.0f);
  EXPECT_EQ(back.at(0, 0, 3), 1.0f);  // RGB file reads back with alpha 1
}

TEST_F(ImageIoTest, Png16RoundTripWithinOneCode) {
  const sb::Image img = testPattern(13, 11);
  const std::string path = file("a16.png");
  sb::writeImage(img, path, sb::ImageBitDepth::U16);
  const sb::Image back = sb::readImage(path);
  ASSERT_EQ(back.width, 13);
  ASSERT_EQ(back.height, 11);
  EXPECT_LE(maxAbsDiff(img, back), 1.0 / 65535.0);
  // Really 16 bit: a value between two 8-bit codes survives.
  sb::Image fine(1, 1, 4, 1000.0f / 65535.0f);
  sb::writeImage(fine, path, sb::ImageBitDepth::U16);
  EXPECT_NEAR(sb::readImage(path).at(0, 0, 0), 1000.0 / 65535.0, 1e-7);
}

TEST_F(ImageIoTest, ExrFloatRoundTripIsExact) {
  sb::Image img = testPattern(19, 7);
  img.at(0, 0, 0) = 1234.5678f;  // out of 0..1 range
  img.at(1, 0, 1) = -3.0e-7f;
  img.at(2, 0, 2) = 1.0f / 3.0f;
  const std::string path = file("a.exr");
  sb::writeImage(img, path);
  const sb::Image back = sb::readImage(path);
  ASSERT_EQ(back.width, img.width);
  ASSERT_EQ(back.height, img.height);
  ASSERT_EQ(back.channels, 4);
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST_F(ImageIoTest, ExrHalfRoundTripWithinHalfPrecision) {
  const sb::Image img = testPattern(8, 8);
  const std::string path = file("h.exr");
  sb::writeImage(img, path, sb::ImageBitDepth::F16);
  EXPECT_LE(maxAbsDiff(img, sb::readImage(path)), 1.0 / 2048.0);
}

TEST_F(ImageIoTest, GreyAndRgbExpandToRgba) {
  sb::Image grey(2, 2, 1, 0.25f);
  sb::writeImage(grey, file("g.exr"));
  const sb::Image g = sb::readImage(file("g.exr"));
  ASSERT_EQ(g.channels, 4);
  EXPECT_EQ(g.at(1, 1, 0), 0.25f);
  EXPECT_EQ(g.at(1, 1, 1), 0.25f);
  EXPECT_EQ(g.at(1, 1, 2), 0.25f);
  EXPECT_EQ(g.at(1, 1, 3), 1.0f);

  sb::Image rgb = testPattern(3, 2, 3);
  sb::writeImage(rgb, file("rgb.exr"));
  const sb::Image r = sb::readImage(file("rgb.exr"));
  for (int c = 0; c < 3; ++c) EXPECT_EQ(r.at(2, 1, c), rgb.at(2, 1, c));
  EXPECT_EQ(r.at(2, 1, 3), 1.0f);
}

TEST_F(ImageIoTest, RowZeroIsTopOfTheFile) {
  // A 1x2 image, top white, bottom black, written and re-read: order kept.
  sb::Image img(1, 2, 4, 1.0f);
  for (int c = 0; c < 3; ++c) img.at(0, 1, c) = 0.0f;
  sb::writeImage(img, file("tb.png"));
  const sb::Image back = sb::readImage(file("tb.png"));
  EXPECT_EQ(back.at(0, 0, 0), 1.0f);
  EXPECT_EQ(back.at(0, 1, 0), 0.0f);
}

TEST_F(ImageIoTest, IdenticalBytesForIdenticalImages) {
  const sb::Image img = testPattern(32, 16);
  const std::vector<std::pair<std::string, sb::ImageBitDepth>> kinds = {
      {".png", sb::ImageBitDepth::U8},
      {".16.png", sb::ImageBitDepth::U16},
      {".exr", sb::ImageBitDepth::F32},
      {".16.exr", sb::ImageBitDepth::F16}};
  for (const auto& [ext, depth] : kinds) sb::writeImage(img, file("one" + ext), depth);
  // Across a clock-second boundary, so an embedded time stamp would show.
  std::this_thread::sleep_for(std::chrono::milliseconds(1100));
  for (const auto& [ext, depth] : kinds) sb::writeImage(img, file("two" + ext), depth);
  for (const auto& [ext, depth] : kinds) {
    const std::string one = slurp(file("one" + ext));
    EXPECT_FALSE(one.empty());
    EXPECT_EQ(one, slurp(file("two" + ext))) << ext;
  }
}

TEST_F(ImageIoTest, OverwriteReplacesTheWholeFile) {
  const std::string path = file("over.png");
  {  // a long junk file first: nothing of it may survive
    std::ofstream junk(path, std::ios::binary);
    junk << std::string(1 << 20, 'x');
  }
  const sb::Image small(2, 2, 4, 0.5f);
  sb::writeImage(small, path);
  sb::writeImage(small, file("fresh.png"));
  EXPECT_EQ(slurp(path), slurp(file("fresh.png")));
  EXPECT_LT(fs::file_size(path), 1000u);

  // And a different image over a real image.
  const sb::Image big = testPattern(64, 64);
  sb::writeImage(big, path);
  const sb::Image back = sb::readImage(path);
  EXPECT_EQ(back.width, 64);
  EXPECT_LE(maxAbsDiff(big, back), 0.5 / 255.0 + 1e-6);
  EXPECT_EQ(entries().size(), 2u);  // over.png, fresh.png; no temporary files
}

TEST_F(ImageIoTest, MissingFolderThrowsAndLeavesNothing) {
  const std::string path = "/nonexistent-dir/x.png";
  try {
    sb::writeImage(sb::Image(2, 2), path);
    FAIL() << "expected InputError";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists("/nonexistent-dir"));

  const std::string inside = file("no/such/folder/x.exr");
  EXPECT_THROW(sb::writeImage(sb::Image(2, 2), inside), sb::InputError);
  EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIoTest, UnwritableFolderThrowsAndLeavesNothing) {
  // A read-only folder; root writes into those, so it gets /proc (no new files there).
  const bool root = ::geteuid() == 0;
  const fs::path ro = root ? fs::path("/proc") : dir_ / "ro";
  if (!root) {
    fs::create_directories(ro);
    fs::permissions(ro, fs::perms::owner_read | fs::perms::owner_exec);
  } else if (!fs::is_directory(ro)) {
    GTEST_SKIP() << "running as root without /proc";
  }
  const std::string path = (ro / "sb-unwritable-test.png").string();
  try {
    sb::writeImage(sb::Image(2, 2), path);
    ADD_FAILURE() << "expected InputError";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(path));
  if (!root) {
    EXPECT_TRUE(fs::is_empty(ro));
    fs::permissions(ro, fs::perms::owner_all);
  }
}

TEST_F(ImageIoTest, UnknownExtensionThrows) {
  for (const std::string name : {"x.jpgx", "x", "x.txt"}) {
    const std::string path = file(name);
    try {
      sb::writeImage(sb::Image(2, 2), path);
      ADD_FAILURE() << "expected InputError for " << name;
    } catch (const sb::InputError& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("extension"), std::string::npos) << e.what();
    }
  }
  EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIoTest, UppercaseExtensionWorks) {
  sb::writeImage(sb::Image(2, 2, 4, 0.5f), file("X.PNG"));
  EXPECT_EQ(sb::readImage(file("X.PNG")).width, 2);
}

TEST_F(ImageIoTest, DepthNotHeldByFormatThrows) {
  EXPECT_THROW(sb::writeImage(sb::Image(2, 2), file("a.png"), sb::ImageBitDepth::F32),
               sb::InputError);
  EXPECT_THROW(sb::writeImage(sb::Image(2, 2), file("a.exr"), sb::ImageBitDepth::U8),
               sb::InputError);
  EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIoTest, InconsistentImageIsRejected) {
  sb::Image bad(2, 2);
  bad.pixels.pop_back();
  EXPECT_THROW(sb::writeImage(bad, file("bad.png")), std::invalid_argument);
  EXPECT_THROW(sb::writeImage(sb::Image(), file("empty.png")), std::invalid_argument);
  EXPECT_TRUE(entries().empty());
}

TEST_F(ImageIoTest, ReadErrorsNameTheFile) {
  const std::string missing = file("missing.png");
  try {
    sb::readImage(missing);
    ADD_FAILURE() << "expected InputError";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(missing), std::string::npos) << e.what();
  }
  const std::string garbage = file("garbage.png");
  {
    std::ofstream out(garbage, std::ios::binary);
    out << "this is not a png";
  }
  try {
    sb::readImage(garbage);
    ADD_FAILURE() << "expected InputError";
  } catch (const sb::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(garbage), std::string::npos) << e.what();
  }
}
