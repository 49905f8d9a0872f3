// `voxgi render` end to end on the Vulkan device: images, timings, warnings, device choice and
// what a failed run leaves behind.

#include <nlohmann/json.hpp>

#include <set>
#include <sstream>

#include "tests/apps/voxgi_cli_fixture.hpp"
#include "tests/scene/gltf_writer.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;

std::set<std::string> files_in(const fs::path& dir) {
  std::set<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
    names.insert(entry.path().filename().string());
  }
  return names;
}

uint32_t big_endian_u32(const std::string& bytes, size_t at) {
  uint32_t value = 0;
  for (size_t i = 0; i < 4; ++i) value = (value << 8) | static_cast<uint8_t>(bytes[at + i]);
  return value;
}

void expect_png(const fs::path& path, uint32_t width, uint32_t height) {
  const std::string bytes = read_text(path);
  ASSERT_GE(bytes.size(), 24u) << path.string();
  EXPECT_EQ(bytes.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8)) << path.string();
  // The first chunk is IHDR: width and height, big-endian.
  EXPECT_EQ(bytes.substr(12, 4), "IHDR") << path.string();
  EXPECT_EQ(big_endian_u32(bytes, 16), width) << path.string();
  EXPECT_EQ(big_endian_u32(bytes, 20), height) << path.string();
}

void expect_exr(const fs::path& path) {
  const std::string bytes = read_text(path);
  ASSERT_GT(bytes.size(), 4u) << path.string();
  EXPECT_EQ(bytes.substr(0, 4), std::string("\x76\x2f\x31\x01", 4)) << path.string();
}

// The scheduled passes, "name (type)", as `voxgi graph explain` prints them.
std::vector<std::pair<std::string, std::string>> scheduled_passes(const std::string& explain) {
  std::vector<std::pair<std::string, std::string>> passes;
  std::istringstream lines(explain.substr(0, explain.find("\nculled (")));
  for (std::string line; std::getline(lines, line);) {
    // "  3. lighting (common.deferred_lighting)"
    const size_t dot = line.find(". ");
    const size_t open = line.find(" (");
    if (line.rfind("  ", 0) != 0 || dot == std::string::npos || open == std::string::npos ||
        line.back() != ')' || line.find_first_not_of(" 0123456789") != dot) {
      continue;
    }
    passes.emplace_back(line.substr(dot + 2, open - dot - 2),
                        line.substr(open + 2, line.size() - open - 3));
  }
  return passes;
}

TEST_F(VoxgiCli, RendersTheCornellBoxWithTimings) {
  const ProcessResult explain = voxgi({"graph", "explain", "graphs/default.json", "--scene",
                                       "cornell", "--width", "64", "--height", "64"});
  ASSERT_TRUE(exited_with(explain, 0));
  const auto schedule = scheduled_passes(explain.out);
  ASSERT_FALSE(schedule.empty()) << explain.describe();

  const ProcessResult r =
      render({"--scene", "cornell", "--out", "render/out", "--timings", "t.json"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(stderr_has(r, {"voxgi: device: ", "voxgi: wrote render/out.png",
                             "voxgi: wrote render/out.exr", "voxgi: wrote t.json"}));
  // Written atomically: no temporary or probe files are left next to the images.
  EXPECT_EQ(files_in(dir_ / "render"),
            (std::set<std::string>{"out.exr", "out-indirect.exr", "out.png"}));
  expect_png(dir_ / "render" / "out.png", 64, 64);
  expect_exr(dir_ / "render" / "out.exr");

  const nlohmann::json timings = nlohmann::json::parse(read_text(dir_ / "t.json"));
  EXPECT_EQ(timings.at("width"), 64);
  EXPECT_EQ(timings.at("height"), 64);
  const nlohmann::json& passes = timings.at("passes");
  ASSERT_TRUE(passes.is_array());
  ASSERT_EQ(passes.size(), schedule.size()) << timings.dump(2) << "\n" << explain.out;
  for (size_t i = 0; i < schedule.size(); ++i) {
    const nlohmann::json& entry = passes[i];
    EXPECT_EQ(entry.at("pass"), schedule[i].first);
    EXPECT_EQ(entry.at("type"), schedule[i].second);
    for (const char* field : {"gpu_ms", "cpu_ms"}) {
      ASSERT_TRUE(entry.at(field).is_number()) << schedule[i].first << "." << field;
      EXPECT_GE(entry.at(field).get<double>(), 0.0) << schedule[i].first << "." << field;
    }
  }
  // The whole frame's own timestamps hold every pass and what lies between them.
  ASSERT_TRUE(timings.at("frame_gpu_ms").is_number());
  ASSERT_TRUE(timings.at("between_passes_gpu_ms").is_number());
  if (timings.at("total_gpu_ms").get<double>() > 0.0) {
    EXPECT_GE(timings.at("frame_gpu_ms").get<double>(),
              0.999 * timings.at("total_gpu_ms").get<double>());
    EXPECT_GE(timings.at("between_passes_gpu_ms").get<double>(), 0.0);
  }
}

TEST_F(VoxgiCli, UnsupportedGltfExtensionWarnsWhenUsedAndIsRefusedWhenRequired) {
  GltfWriter writer;
  nlohmann::json primitive = writer.triangle();
  primitive["material"] = 0;
  writer.add_mesh_node(primitive);
  writer.doc["materials"] = nlohmann::json::array(
      {{{"pbrMetallicRoughness", {{"baseColorFactor", {0.8, 0.8, 0.8, 1.0}}}},
        {"extensions", {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}}}}}});
  writer.doc["extensionsUsed"] = {"KHR_materials_transmission"};
  writer.write_gltf(dir_ / "glass.gltf");

  const ProcessResult r = render({"--scene", "glass.gltf", "--out", "glass"});
  ASSERT_TRUE(exited_with(r, 0));
  EXPECT_TRUE(
      stderr_has(r, {"voxgi: warning: glass.gltf: extensionsUsed:", "KHR_materials_transmission"}));
  expect_png(dir_ / "glass.png", 64, 64);

  // The same extension required by the file: refused, and nothing written.
  writer.doc["extensionsRequired"] = {"KHR_materials_transmission"};
  writer.write_gltf(dir_ / "required.gltf");
  const ProcessResult refused = render({"--scene", "required.gltf", "--out", "required"});
  ASSERT_TRUE(exited_with(refused, 1));
  EXPECT_TRUE(stderr_has(refused, {"required.gltf: extensionsRequired: unsupported extension",
                                   "KHR_materials_transmission"}));
  EXPECT_FALSE(std::filesystem::exists(dir_ / "required.png"));
}

TEST_F(VoxgiCli, UnknownDeviceListsTheAvailableDevices) {
  const ProcessResult devices = voxgi({"devices"});
  ASSERT_TRUE(exited_with(devices, 0));
  std::vector<std::string> listed;
  std::istringstream lines(devices.out);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty()) listed.push_back(line);
  }
  ASSERT_FALSE(listed.empty()) << devices.describe();

  const ProcessResult r = render({"--device", "nosuchdevice", "--out", "out/image"});
  EXPECT_TRUE(exited_with(r, 1));
  EXPECT_TRUE(stderr_has(r, {"--device \"nosuchdevice\"", "available devices"}));
  EXPECT_TRUE(stderr_has(r, listed));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "image.png"));
}

TEST_F(VoxgiCli, FailedRunsKeepTheImagesOfAnEarlierRun) {
  const ProcessResult first = render({"--out", "keep/out"});
  ASSERT_TRUE(exited_with(first, 0));
  const std::string png = read_text(dir_ / "keep" / "out.png");
  const std::string exr = read_text(dir_ / "keep" / "out.exr");
  ASSERT_FALSE(png.empty());
  ASSERT_FALSE(exr.empty());

  // Each would write different images (another size) if it got as far as writing.
  const std::vector<std::vector<std::string>> failing = {
      {"--scene", "missing.gltf"},
      {"--set", "lighting.pcf_radius=99"},
      {"--device", "nosuchdevice"},
      // The timings folder cannot be created: its place is taken by the earlier image.
      {"--timings", "keep/out.png/t.json"},
  };
  for (const std::vector<std::string>& extra : failing) {
    std::vector<std::string> args = {"render", "--width",      "32",    "--height",
                                     "32",     "--validation", "--out", "keep/out"};
    args.insert(args.end(), extra.begin(), extra.end());
    const ProcessResult r = voxgi(args);
    EXPECT_TRUE(exited_with(r, 1)) << extra.front();
    EXPECT_FALSE(contains(r.err, "voxgi: wrote")) << r.describe();
    EXPECT_EQ(read_text(dir_ / "keep" / "out.png"), png) << "after " << extra.front();
    EXPECT_EQ(read_text(dir_ / "keep" / "out.exr"), exr) << "after " << extra.front();
    EXPECT_EQ(files_in(dir_ / "keep"),
              (std::set<std::string>{"out.exr", "out-indirect.exr", "out.png"}));
  }
}

}  // namespace
}  // namespace voxgi::test
