#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <fstream>
#include <limits>

#include "engine/image/image.hpp"

namespace voxgi::image {
namespace {

class ImageFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    static int counter = 0;
    dir_ = std::filesystem::temp_directory_path() /
           ("voxgi-image-" + std::to_string(getpid()) + "-" + std::to_string(counter++));
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all,
                                 std::filesystem::perm_options::add, ec);
    std::filesystem::remove_all(dir_, ec);
  }
  std::filesystem::path dir_;
};

ImageRGBA32F gradient(uint32_t w, uint32_t h) {
  ImageRGBA32F image(w, h);
  for (uint32_t y = 0; y < h; ++y) {
    for (uint32_t x = 0; x < w; ++x) {
      float* p = image.at(x, y);
      p[0] = float(x) / float(w - 1);
      p[1] = float(y) / float(h - 1);
      p[2] = 0.25f;
      p[3] = 1.0f;
    }
  }
  return image;
}

size_t temp_files(const std::filesystem::path& dir) {
  size_t n = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().filename().string().find(".tmp-") != std::string::npos) ++n;
  }
  return n;
}

TEST_F(ImageFiles, PngRoundTripQuantizesWithRounding) {
  ImageRGBA32F image = gradient(7, 5);
  image.at(0, 0)[0] = 2.0f;                                     // clamps to 1
  image.at(1, 0)[0] = -1.0f;                                    // clamps to 0
  image.at(2, 0)[0] = std::numeric_limits<float>::quiet_NaN();  // writes 0
  image.at(3, 0)[0] = 0.5f / 255.0f + 1e-4f;                    // rounds up to 1
  const auto path = dir_ / "out.png";
  write_png(path, image);
  const ImageRGBA32F back = read_png(path);
  ASSERT_EQ(back.width, 7u);
  ASSERT_EQ(back.height, 5u);
  for (uint32_t y = 0; y < 5; ++y) {
    for (uint32_t x = (y == 0 ? 4 : 0); x < 7; ++x) {
      for (int c = 0; c < 4; ++c) {
        EXPECT_NEAR(back.at(x, y)[c], image.at(x, y)[c], 0.5f / 255.0f + 1e-6f);
      }
    }
  }
  EXPECT_EQ(back.at(0, 0)[0], 1.0f);
  EXPECT_EQ(back.at(1, 0)[0], 0.0f);
  EXPECT_EQ(back.at(2, 0)[0], 0.0f);
  EXPECT_EQ(back.at(3, 0)[0], 1.0f / 255.0f);
  EXPECT_EQ(temp_files(dir_), 0u);
}

TEST_F(ImageFiles, ExrRoundTripHalfAndFloat) {
  ImageRGBA32F image = gradient(9, 4);
  image.at(1, 1)[0] = 1000.5f;
  image.at(2, 1)[1] = 1e-3f;
  write_exr(dir_ / "half.exr", image);
  write_exr(dir_ / "float.exr", image, ExrPixelType::Float);
  const ImageRGBA32F half = read_exr(dir_ / "half.exr");
  const ImageRGBA32F full = read_exr(dir_ / "float.exr");
  ASSERT_EQ(half.width, 9u);
  ASSERT_EQ(half.height, 4u);
  EXPECT_EQ(full.pixels, image.pixels);
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    EXPECT_NEAR(half.pixels[i], image.pixels[i], std::abs(image.pixels[i]) * 1e-3f + 1e-6f);
  }
  EXPECT_EQ(exr_layers(dir_ / "half.exr"), std::vector<std::string>{""});
  EXPECT_THROW(read_exr(dir_ / "half.exr", "Indirect"), ImageError);
}

TEST_F(ImageFiles, NonFiniteCount) {
  ImageRGBA32F image = gradient(4, 4);
  size_t count = 99;
  EXPECT_FALSE(has_non_finite(image, &count));
  EXPECT_EQ(count, 0u);
  image.at(1, 1)[2] = std::numeric_limits<float>::infinity();
  image.at(2, 1)[0] = std::numeric_limits<float>::quiet_NaN();
  image.at(2, 1)[1] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_TRUE(has_non_finite(image, &count));
  EXPECT_EQ(count, 2u);
  EXPECT_TRUE(has_non_finite(image));
}

TEST_F(ImageFiles, MissingDirectoryNamesPathAndReason) {
  const auto path = dir_ / "no" / "such" / "dir" / "x.png";
  try {
    write_png(path, gradient(2, 2));
    FAIL() << "expected ImageError";
  } catch (const ImageError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  }
  EXPECT_THROW(write_exr(path.parent_path() / "x.exr", gradient(2, 2)), ImageError);
}

TEST_F(ImageFiles, FailedWriteKeepsTheExistingFile) {
  const auto png = dir_ / "keep.png";
  const auto exr = dir_ / "keep.exr";
  write_png(png, gradient(3, 3));
  write_exr(exr, gradient(3, 3));
  const auto png_size = std::filesystem::file_size(png);
  const auto exr_size = std::filesystem::file_size(exr);
  // A bad image fails before touching anything.
  ImageRGBA32F broken(4, 4);
  broken.pixels.resize(5);
  EXPECT_THROW(write_png(png, broken), ImageError);
  // An unwritable directory fails with the reason, and the old files survive.
  std::filesystem::permissions(dir_, std::filesystem::perms::owner_write,
                               std::filesystem::perm_options::remove);
  const bool root = geteuid() == 0;  // root ignores directory permissions
  if (!root) {
    try {
      write_png(png, gradient(8, 8));
      FAIL() << "expected ImageError";
    } catch (const ImageError& e) {
      EXPECT_NE(std::string(e.what()).find(png.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("ermission denied"), std::string::npos) << e.what();
    }
    EXPECT_THROW(write_exr(exr, gradient(8, 8)), ImageError);
  }
  std::filesystem::permissions(dir_, std::filesystem::perms::owner_write,
                               std::filesystem::perm_options::add);
  EXPECT_EQ(std::filesystem::file_size(png), png_size);
  EXPECT_EQ(std::filesystem::file_size(exr), exr_size);
  EXPECT_EQ(read_png(png).width, 3u);
  EXPECT_EQ(read_exr(exr).width, 3u);
  EXPECT_EQ(temp_files(dir_), 0u);
}

TEST_F(ImageFiles, ReadErrorsNameThePath) {
  EXPECT_THROW(read_png(dir_ / "missing.png"), ImageError);
  EXPECT_THROW(read_exr(dir_ / "missing.exr"), ImageError);
  std::ofstream(dir_ / "junk.png") << "junk";
  std::ofstream(dir_ / "junk.exr") << "junk";
  try {
    read_exr(dir_ / "junk.exr");
    FAIL();
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("junk.exr"), std::string::npos);
  }
  try {
    read_png(dir_ / "junk.png");
    FAIL();
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("junk.png"), std::string::npos);
  }
}

TEST(ReferenceImages, MultilayerPassesRead) {
  const std::filesystem::path refs = std::filesystem::path(VOXGI_SHARED_DIR) / "references";
  const auto passes = refs / "cornell-box-camera-256x256-passes.exr";
  const auto beauty = refs / "cornell-box-camera-256x256.exr";
  if (!std::filesystem::exists(passes) || !std::filesystem::exists(beauty)) {
    GTEST_SKIP() << "shared reference images not available in " << refs;
  }
  const auto layers = exr_layers(passes);
  for (const char* name : {"Combined", "Direct", "Indirect"}) {
    EXPECT_NE(std::find(layers.begin(), layers.end(), name), layers.end()) << name;
  }
  const ImageRGBA32F combined = read_exr(passes, "Combined");
  const ImageRGBA32F direct = read_exr(passes, "Direct");
  const ImageRGBA32F indirect = read_exr(passes, "Indirect");
  const ImageRGBA32F plain = read_exr(beauty);
  ASSERT_EQ(combined.width, 256u);
  ASSERT_EQ(combined.height, 256u);
  EXPECT_EQ(plain.width, 256u);
  EXPECT_FALSE(has_non_finite(combined));
  // Combined = Direct + Indirect (README: to 5e-6), and the default layer is Combined.
  double max_error = 0.0, sum = 0.0;
  for (size_t i = 0; i < combined.pixels.size(); i += 4) {
    for (int c = 0; c < 3; ++c) {
      max_error = std::max(
          max_error,
          double(std::abs(combined.pixels[i + c] - direct.pixels[i + c] - indirect.pixels[i + c])));
      sum += combined.pixels[i + c];
    }
  }
  EXPECT_LT(max_error, 1e-3);
  EXPECT_GT(sum, 0.0);
  EXPECT_EQ(read_exr(passes).pixels, combined.pixels);
  try {
    read_exr(passes, "Nope");
    FAIL();
  } catch (const ImageError& e) {
    EXPECT_NE(std::string(e.what()).find("Indirect"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace voxgi::image
