// The interleaved cone sets' layout on the device (shaders/vct/interleave_layout.glsl through
// tests/vct/shaders/interleave_probe.comp): which turn i and ring position j of the n x n sets
// each pixel traces, for every window size vct.cone_trace accepts.

#include <gtest/gtest.h>

#include <glm/glm.hpp>

#include <filesystem>
#include <set>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/gpu/shader_compiler.hpp"
#include "tests/gpu/buffer_probe.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

namespace fs = std::filesystem;

class InterleaveLayoutTest : public GpuTest {
 protected:
  // (i, j) of pixel (x, y), x and y in [0, 2n): the probe's 2n x 2n block.
  std::vector<glm::ivec2> cells(int n) {
    gpu::ShaderCompiler compiler({fs::path(VOXGI_SOURCE_DIR) / "tests" / "vct" / "shaders",
                                  fs::path(VOXGI_SOURCE_DIR) / "shaders"},
                                 "");
    const auto count = static_cast<uint32_t>(4 * n * n);
    gpu::Buffer input(context(), sizeof(int32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                      gpu::MemoryUsage::GpuOnly, "test.unused");
    gpu::Buffer output(context(), count * sizeof(glm::ivec2), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                       gpu::MemoryUsage::GpuOnly, "test.interleave_cells");
    run_buffer_probe(compiler, "interleave_probe.comp", input, output, static_cast<uint32_t>(n));
    return output.download_vector<glm::ivec2>(count);
  }
};

// Every n x n window, wherever it starts (interleave.comp centres it on each pixel), traces
// each turn and each ring position once, and its n^2 (turn, ring) pairs fall one into each of
// the n x n blocks of the (turn, ring) square.
TEST_F(InterleaveLayoutTest, EveryWindowHoldsEachTurnAndRingPositionOnce) {
  for (int n = 1; n <= 4; ++n) {
    const std::vector<glm::ivec2> c = cells(n);
    for (int oy = 0; oy < n; ++oy) {
      for (int ox = 0; ox < n; ++ox) {
        std::set<int> turns, rings, blocks;
        for (int y = oy; y < oy + n; ++y) {
          for (int x = ox; x < ox + n; ++x) {
            const glm::ivec2 cell = c[y * 2 * n + x];
            ASSERT_GE(cell.x, 0);
            ASSERT_LT(cell.x, n * n);
            ASSERT_GE(cell.y, 0);
            ASSERT_LT(cell.y, n * n);
            turns.insert(cell.x);
            rings.insert(cell.y);
            blocks.insert((cell.x / n) * n + cell.y / n);
          }
        }
        const auto all = static_cast<size_t>(n * n);
        EXPECT_EQ(turns.size(), all) << "n " << n << ", window at " << ox << ", " << oy;
        EXPECT_EQ(rings.size(), all) << "n " << n << ", window at " << ox << ", " << oy;
        EXPECT_EQ(blocks.size(), all) << "n " << n << ", window at " << ox << ", " << oy;
      }
    }
  }
}

// A surface one pixel wide averages one row or column of the window: it must still see the
// scene from all around (one turn from each n-th of the circle) and at every polar angle (one
// position from each n-th of the ring). Order 2 has no pair of orthogonal Latin squares, so it
// is left out. For n = 4, each aligned 2 x 2 block also holds one of each quarter.
TEST_F(InterleaveLayoutTest, EveryRowAndColumnSpansTheCircleAndTheRing) {
  for (int n : {3, 4}) {
    const std::vector<glm::ivec2> c = cells(n);
    for (int line = 0; line < 2 * n; ++line) {
      for (int start = 0; start < n; ++start) {
        std::set<int> row_turns, row_rings, column_turns, column_rings;
        for (int k = start; k < start + n; ++k) {
          row_turns.insert(c[line * 2 * n + k].x / n);
          row_rings.insert(c[line * 2 * n + k].y / n);
          column_turns.insert(c[k * 2 * n + line].x / n);
          column_rings.insert(c[k * 2 * n + line].y / n);
        }
        const auto all = static_cast<size_t>(n);
        EXPECT_EQ(row_turns.size(), all) << "n " << n << ", row " << line << " from " << start;
        EXPECT_EQ(row_rings.size(), all) << "n " << n << ", row " << line << " from " << start;
        EXPECT_EQ(column_turns.size(), all)
            << "n " << n << ", column " << line << " from " << start;
        EXPECT_EQ(column_rings.size(), all)
            << "n " << n << ", column " << line << " from " << start;
      }
    }
  }
  const std::vector<glm::ivec2> c = cells(4);
  for (int by = 0; by < 8; by += 2) {
    for (int bx = 0; bx < 8; bx += 2) {
      std::set<int> turns, rings;
      for (int y = by; y < by + 2; ++y) {
        for (int x = bx; x < bx + 2; ++x) {
          turns.insert(c[y * 8 + x].x / 4);
          rings.insert(c[y * 8 + x].y / 4);
        }
      }
      EXPECT_EQ(turns.size(), 4u) << "2 x 2 block at " << bx << ", " << by;
      EXPECT_EQ(rings.size(), 4u) << "2 x 2 block at " << bx << ", " << by;
    }
  }
}

}  // namespace
}  // namespace voxgi::test
