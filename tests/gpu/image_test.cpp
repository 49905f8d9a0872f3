#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "engine/gpu/error.hpp"
#include "engine/gpu/image.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

using ImageTest = GpuTest;

template <typename T>
std::vector<T> as(const std::vector<uint8_t>& bytes) {
  std::vector<T> values(bytes.size() / sizeof(T));
  std::memcpy(values.data(), bytes.data(), values.size() * sizeof(T));
  return values;
}

template <typename T>
std::vector<uint8_t> bytes_of(const std::vector<T>& values) {
  std::vector<uint8_t> bytes(values.size() * sizeof(T));
  std::memcpy(bytes.data(), values.data(), bytes.size());
  return bytes;
}

TEST(ImageFormatTest, SizesAndAspects) {
  EXPECT_EQ(gpu::full_mip_count({1, 1, 1}), 1u);
  EXPECT_EQ(gpu::full_mip_count({64, 32, 1}), 7u);
  EXPECT_EQ(gpu::full_mip_count({5, 3, 1}), 3u);
  EXPECT_EQ(gpu::full_mip_count({4, 4, 64}), 7u);
  EXPECT_EQ(gpu::bytes_per_texel(VK_FORMAT_R8G8B8A8_SRGB), 4u);
  EXPECT_EQ(gpu::bytes_per_texel(VK_FORMAT_R16G16B16A16_SFLOAT), 8u);
  EXPECT_EQ(gpu::bytes_per_texel(VK_FORMAT_R32G32B32A32_UINT), 16u);
  EXPECT_EQ(gpu::bytes_per_texel(VK_FORMAT_B10G11R11_UFLOAT_PACK32), 4u);
  EXPECT_EQ(gpu::bytes_per_texel(VK_FORMAT_D16_UNORM), 2u);
  EXPECT_THROW(gpu::bytes_per_texel(VK_FORMAT_BC1_RGB_UNORM_BLOCK), gpu::Error);
  EXPECT_TRUE(gpu::is_depth_format(VK_FORMAT_D32_SFLOAT));
  EXPECT_FALSE(gpu::is_depth_format(VK_FORMAT_R32_SFLOAT));
  EXPECT_EQ(gpu::aspect_of(VK_FORMAT_D16_UNORM), VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT));
  EXPECT_EQ(gpu::aspect_of(VK_FORMAT_R8_UNORM), VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT));
  EXPECT_EQ(gpu::mip_extent({16, 4, 1}, 3).width, 2u);
  EXPECT_EQ(gpu::mip_extent({16, 4, 1}, 3).height, 1u);
}

TEST_F(ImageTest, Rgba8RoundTrip) {
  gpu::Image image(context(), {VK_IMAGE_TYPE_2D,
                               VK_FORMAT_R8G8B8A8_UNORM,
                               {16, 8, 1},
                               1,
                               1,
                               VK_IMAGE_USAGE_SAMPLED_BIT,
                               "test.rgba8"});
  std::vector<uint8_t> pixels(16 * 8 * 4);
  for (size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<uint8_t>(i * 7);
  image.upload(pixels.data(), pixels.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(image.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL), pixels);
  EXPECT_NE(image.view(), VK_NULL_HANDLE);
  EXPECT_EQ(image.view(0), image.view(0));
  EXPECT_GE(image.memory_size(), pixels.size());
}

TEST_F(ImageTest, Rgba32fRoundTrip) {
  gpu::Image image(context(), {VK_IMAGE_TYPE_2D,
                               VK_FORMAT_R32G32B32A32_SFLOAT,
                               {8, 8, 1},
                               1,
                               1,
                               VK_IMAGE_USAGE_STORAGE_BIT,
                               "test.rgba32f"});
  std::vector<float> texels(8 * 8 * 4);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = float(i) * 0.25f - 3.0f;
  auto bytes = bytes_of(texels);
  image.upload(bytes.data(), bytes.size(), VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(as<float>(image.download(VK_IMAGE_LAYOUT_GENERAL)), texels);
}

TEST_F(ImageTest, Volume3dR32fRoundTrip) {
  gpu::Image image(context(), {VK_IMAGE_TYPE_3D,
                               VK_FORMAT_R32_SFLOAT,
                               {8, 4, 6},
                               1,
                               1,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_STORAGE_BIT,
                               "test.volume"});
  std::vector<float> voxels(8 * 4 * 6);
  for (size_t i = 0; i < voxels.size(); ++i) voxels[i] = float(i) + 0.5f;
  auto bytes = bytes_of(voxels);
  image.upload(bytes.data(), bytes.size(), VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(as<float>(image.download(VK_IMAGE_LAYOUT_GENERAL)), voxels);
  EXPECT_NE(image.view(), VK_NULL_HANDLE);
  EXPECT_THROW(image.layer_view(0), gpu::Error);
}

TEST_F(ImageTest, ArrayLayersAndUploadMip) {
  gpu::Image image(context(), {VK_IMAGE_TYPE_2D,
                               VK_FORMAT_R32_UINT,
                               {4, 4, 1},
                               3,
                               2,
                               VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                               "test.layers"});
  std::vector<uint32_t> texels(4 * 4 * 2);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = uint32_t(i * 3);
  auto bytes = bytes_of(texels);
  image.upload(bytes.data(), bytes.size(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  auto layer1 = as<uint32_t>(image.download(VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, 0, 1));
  EXPECT_EQ(layer1, std::vector<uint32_t>(texels.begin() + 16, texels.end()));
  std::vector<uint32_t> mip1{11, 22, 33, 44};
  auto mip_bytes = bytes_of(mip1);
  image.upload_mip(mip_bytes.data(), mip_bytes.size(), 1, 1, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(as<uint32_t>(image.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 1, 1)), mip1);
  // Mip 0 survived the mip-1 upload.
  EXPECT_EQ(as<uint32_t>(image.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, 1)), layer1);
  EXPECT_NE(image.layer_view(1, 2), VK_NULL_HANDLE);
  EXPECT_EQ(image.layer_view(1, 2), image.layer_view(1, 2));
  EXPECT_NE(image.layer_view(0), image.layer_view(1));
  EXPECT_THROW(image.layer_view(2), gpu::Error);
  EXPECT_THROW(image.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 3, 0), gpu::Error);
}

TEST_F(ImageTest, CubeViews) {
  gpu::ImageDesc desc{VK_IMAGE_TYPE_2D,
                      VK_FORMAT_D32_SFLOAT,
                      {8, 8, 1},
                      1,
                      6,
                      VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                      "test.cube"};
  desc.flags = VK_IMAGE_CREATE_CUBE_COMPATIBLE_BIT;
  gpu::Image cube(context(), desc);
  EXPECT_EQ(cube.aspect(), VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT));
  EXPECT_NE(cube.view(), VK_NULL_HANDLE);
  EXPECT_NE(cube.layer_view(5), VK_NULL_HANDLE);
  std::vector<float> depths(8 * 8 * 6, 0.25f);
  auto bytes = bytes_of(depths);
  cube.upload(bytes.data(), bytes.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(as<float>(cube.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 0, 4)),
            std::vector<float>(64, 0.25f));
}

TEST_F(ImageTest, GenerateMipsAveragesTwoByTwo) {
  {
    gpu::Image image(context(), {VK_IMAGE_TYPE_2D,
                                 VK_FORMAT_R8G8B8A8_UNORM,
                                 {2, 2, 1},
                                 0,
                                 1,
                                 VK_IMAGE_USAGE_SAMPLED_BIT,
                                 "test.mips8"});
    ASSERT_EQ(image.desc().mip_levels, 2u);
    ASSERT_TRUE(image.can_generate_mips());
    std::vector<uint8_t> pixels{0,  40,  200, 255, 100, 80,  200, 255,
                                20, 120, 0,   255, 120, 160, 0,   255};
    image.upload(pixels.data(), pixels.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, true);
    auto mip = image.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 1);
    ASSERT_EQ(mip.size(), 4u);
    const int expected[4] = {60, 100, 100, 255};
    for (int c = 0; c < 4; ++c) EXPECT_NEAR(mip[c], expected[c], 1) << "channel " << c;
  }
  for (VkFormat format :
       {VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R16G16B16A16_SFLOAT, VK_FORMAT_R8G8B8A8_SRGB}) {
    gpu::Image image(
        context(),
        {VK_IMAGE_TYPE_2D, format, {4, 4, 1}, 0, 1, VK_IMAGE_USAGE_SAMPLED_BIT, "test.mips"});
    EXPECT_TRUE(image.can_generate_mips()) << gpu::format_name(format);
  }
  gpu::Image image(context(), {VK_IMAGE_TYPE_2D,
                               VK_FORMAT_R32G32B32A32_SFLOAT,
                               {2, 2, 1},
                               2,
                               1,
                               VK_IMAGE_USAGE_SAMPLED_BIT,
                               "test.mips32"});
  std::vector<float> texels{1, 2, 3, 4, 5, 6, 7, 8, -1, 0, 1, 2, 3, 0, 0, 2};
  auto bytes = bytes_of(texels);
  image.upload(bytes.data(), bytes.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, true);
  auto mip = as<float>(image.download(VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 1));
  ASSERT_EQ(mip.size(), 4u);
  const float expected[4] = {2.0f, 2.0f, 2.75f, 4.0f};
  for (int c = 0; c < 4; ++c) EXPECT_NEAR(mip[c], expected[c], 1e-5f) << "channel " << c;
}

TEST_F(ImageTest, BadDescriptionsAndSizesThrow) {
  EXPECT_THROW(gpu::Image(context(), {VK_IMAGE_TYPE_2D,
                                      VK_FORMAT_R8_UNORM,
                                      {0, 4, 1},
                                      1,
                                      1,
                                      VK_IMAGE_USAGE_SAMPLED_BIT,
                                      "test.zero"}),
               gpu::Error);
  EXPECT_THROW(gpu::Image(context(), {VK_IMAGE_TYPE_2D,
                                      VK_FORMAT_R8_UNORM,
                                      {4, 4, 1},
                                      9,
                                      1,
                                      VK_IMAGE_USAGE_SAMPLED_BIT,
                                      "test.mips"}),
               gpu::Error);
  try {
    gpu::Image(context(), {VK_IMAGE_TYPE_2D,
                           VK_FORMAT_R8G8B8A8_SRGB,
                           {4, 4, 1},
                           1,
                           1,
                           VK_IMAGE_USAGE_STORAGE_BIT,
                           "test.srgb_storage"});
    // Some devices can store to sRGB; then there is nothing to check.
  } catch (const gpu::Error& error) {
    std::string message = error.what();
    EXPECT_NE(message.find("test.srgb_storage"), std::string::npos) << message;
    EXPECT_NE(message.find("VK_FORMAT_R8G8B8A8_SRGB"), std::string::npos) << message;
  }
  gpu::Image image(context(), {VK_IMAGE_TYPE_2D,
                               VK_FORMAT_R8_UNORM,
                               {4, 4, 1},
                               1,
                               1,
                               VK_IMAGE_USAGE_SAMPLED_BIT,
                               "test.size"});
  std::vector<uint8_t> wrong(15);
  try {
    image.upload(wrong.data(), wrong.size(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    FAIL() << "expected gpu::Error";
  } catch (const gpu::Error& error) {
    EXPECT_NE(std::string(error.what()).find("expected 16"), std::string::npos) << error.what();
  }
  EXPECT_THROW(image.download(VK_IMAGE_LAYOUT_UNDEFINED), gpu::Error);
}

}  // namespace
}  // namespace voxgi::test
