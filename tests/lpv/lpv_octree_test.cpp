// The octree LPV (seed 002 sec. 4.2) through tests/lpv/graphs/propagation.json on the Cornell
// box, 16^3 cells and three octree levels (16, 8, 4), the buffers read back: each level after
// lpv.downsample is the mean of its children and its geometry their surface; the index marks
// after lpv.propagate are exactly the cells within each level's steps of its injected cells;
// lpv.merge reproduces eq. 10 (index) and the sum of the levels (shells).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <deque>
#include <string>
#include <vector>

#include "engine/gpu/buffer.hpp"
#include "engine/graph/executor.hpp"
#include "tests/common/render_harness.hpp"
#include "tests/gpu/gpu_test_env.hpp"

namespace voxgi::test {
namespace {

constexpr int kResolution = 16;
constexpr int kLevels = 3;
constexpr size_t kRecordFloats = 20;  // lpv/cells.glsl, LPV_RECORD_VEC4S

// A cell record: SH r, g, b (4 floats each), stopped flux (rgb) and index mark (w), geometry.
struct Record {
  const float* f;
  float sh(int i) const { return f[i]; }  // 12 floats: r, g, b
  float mark() const { return f[15]; }
  float opacity() const { return f[19]; }
  bool lit() const {
    return std::any_of(f, f + 12, [](float v) { return v != 0.0f; });
  }
};

int level_resolution(int o) {
  return kResolution >> o;
}

size_t level_base(int o) {
  size_t base = 0;
  for (int i = 0; i < o; ++i) base += static_cast<size_t>(std::pow(level_resolution(i), 3));
  return base;
}

size_t cell(int x, int y, int z, int o) {
  const int n = level_resolution(o);
  return level_base(o) + (static_cast<size_t>(z) * n + y) * n + x;
}

class OctreeBuffers {
 public:
  OctreeBuffers(RenderHarness& harness) {
    for (auto [name, data] :
         {std::pair{"lpv.injected_levels", &injected_}, std::pair{"lpv.levels", &levels_},
          std::pair{"lpv.radiance", &merged_}}) {
      gpu::Buffer* buffer = harness.executor().buffer(name);
      EXPECT_NE(buffer, nullptr) << name;
      if (buffer) *data = buffer->download_vector<float>(buffer->size() / 4);
    }
  }
  Record injected(size_t c) const { return {injected_.data() + c * kRecordFloats}; }
  Record levels(size_t c) const { return {levels_.data() + c * kRecordFloats}; }
  Record merged(size_t c) const { return {merged_.data() + c * kRecordFloats}; }
  bool complete() const {
    const size_t need = level_base(kLevels) * kRecordFloats;
    return injected_.size() >= need && levels_.size() >= need &&
           merged_.size() >= level_base(1) * kRecordFloats;
  }

 private:
  std::vector<float> injected_, levels_, merged_;
};

RenderSetup octree_setup(int iterations, const char* merge, bool occlusion) {
  RenderSetup setup;
  setup.graph = "tests/lpv/graphs/propagation.json";
  setup.scene = "cornell";
  setup.width = setup.height = 16;
  setup.overrides["voxel.resolution"] = std::to_string(kResolution);
  setup.overrides["lpv.octree_levels"] = std::to_string(kLevels);
  setup.overrides["lpv.iterations"] = std::to_string(iterations);
  setup.overrides["lpv.occlusion"] = occlusion ? "true" : "false";
  setup.overrides["propagate.merge"] = merge;
  setup.overrides["merge.merge"] = merge;
  return setup;
}

// The steps of level o (passes/lpv/propagate_pass.cpp): k on level 0, at most the 3 (n - 1)
// that cross a coarser level; the index merge runs no level further.
int index_merge_steps(int o, int k) {
  return o == 0 ? k : std::min(k, 3 * (level_resolution(o) - 1));
}

// Eq. 11 on the injection and the geometry volume's coverage rule (lpv/downsample.comp).
TEST_F(GpuTest, LpvOctreeLevelsAreTheMeanOfTheirChildren) {
  RenderHarness harness(octree_setup(2, "index", true));
  harness.render();
  const OctreeBuffers buffers(harness);
  ASSERT_TRUE(buffers.complete());
  int lit_cells = 0;
  double worst = 0.0;
  for (int o = 1; o < kLevels; ++o) {
    const int n = level_resolution(o);
    for (int z = 0; z < n; ++z) {
      for (int y = 0; y < n; ++y) {
        for (int x = 0; x < n; ++x) {
          const Record coarse = buffers.injected(cell(x, y, z, o));
          float mean[12] = {};
          float opacity = 0.0f;
          for (int k = 0; k < 8; ++k) {
            const Record child = buffers.injected(
                cell(2 * x + (k & 1), 2 * y + ((k >> 1) & 1), 2 * z + (k >> 2), o - 1));
            for (int i = 0; i < 12; ++i) mean[i] += child.sh(i) / 8.0f;
            opacity += child.opacity();
          }
          for (int i = 0; i < 12; ++i) {
            const double error = std::abs(coarse.sh(i) - mean[i]);
            worst = std::max(worst, error / std::max(1e-6, static_cast<double>(std::abs(mean[i]))));
            ASSERT_NEAR(coarse.sh(i), mean[i], 1e-5 * std::abs(mean[i]) + 1e-12)
                << "level " << o << " cell " << x << "," << y << "," << z << " coefficient " << i;
          }
          ASSERT_NEAR(coarse.opacity(), std::min(1.0f, opacity / 4.0f), 1e-6f);
          ASSERT_EQ(coarse.mark(), coarse.lit() ? static_cast<float>(o) : -1.0f);
          lit_cells += coarse.lit() ? 1 : 0;
        }
      }
    }
  }
  std::printf("octree downsampling: %d lit coarse cells, worst relative error %.2g\n", lit_cells,
              worst);
  EXPECT_GT(lit_cells, 0);
}

// Without the geometry volume light lands in exactly the cells within a level's steps (6-
// neighbour steps) of a cell injected on that level: the index volume after k steps. Then no
// cell's index exceeds the first level whose cells light crosses in k steps, 3 (n - 1) <= k
// (the seed's bound l - 1 - floor(log2 k) counts n - 1 steps, along an axis only). The index
// merge takes, per level-0 cell, the finest level whose cell is lit, and 2^o times its record.
TEST_F(GpuTest, LpvOctreeIndexVolumeAndMergeFollowEquationTen) {
  for (int k : {1, 2, 21}) {
    RenderHarness harness(octree_setup(k, "index", false));
    harness.render();
    const OctreeBuffers buffers(harness);
    ASSERT_TRUE(buffers.complete());
    int complete_level = kLevels - 1;
    for (int o = 0; o < kLevels; ++o) {
      if (3 * (level_resolution(o) - 1) <= k) {
        complete_level = o;
        break;
      }
    }
    for (int o = 0; o < kLevels; ++o) {
      // Distance in steps from the level's injected cells (breadth first).
      const int n = level_resolution(o);
      std::vector<int> distance(static_cast<size_t>(n) * n * n, -1);
      std::deque<int> queue;
      for (int i = 0; i < n * n * n; ++i) {
        if (buffers.injected(level_base(o) + i).lit()) {
          distance[i] = 0;
          queue.push_back(i);
        }
      }
      while (!queue.empty()) {
        const int i = queue.front();
        queue.pop_front();
        const int x = i % n, y = (i / n) % n, z = i / (n * n);
        const int next[6][3] = {{x + 1, y, z}, {x - 1, y, z}, {x, y + 1, z},
                                {x, y - 1, z}, {x, y, z + 1}, {x, y, z - 1}};
        for (const auto& c : next) {
          if (std::min({c[0], c[1], c[2]}) < 0 || std::max({c[0], c[1], c[2]}) >= n) continue;
          const int j = (c[2] * n + c[1]) * n + c[0];
          if (distance[j] >= 0) continue;
          distance[j] = distance[i] + 1;
          queue.push_back(j);
        }
      }
      int mismatches = 0;
      for (int i = 0; i < n * n * n; ++i) {
        const bool expected = distance[i] >= 0 && distance[i] <= index_merge_steps(o, k);
        const float mark = buffers.levels(level_base(o) + i).mark();
        if (mark != (expected ? static_cast<float>(o) : -1.0f)) ++mismatches;
      }
      EXPECT_EQ(mismatches, 0) << "k " << k << ", level " << o << ": index marks";
    }
    int worst_index = 0, mismatches = 0;
    for (int z = 0; z < kResolution; ++z) {
      for (int y = 0; y < kResolution; ++y) {
        for (int x = 0; x < kResolution; ++x) {
          int chosen = kLevels - 1;
          for (int o = 0; o < kLevels; ++o) {
            if (buffers.levels(cell(x >> o, y >> o, z >> o, o)).mark() >= 0.0f) {
              chosen = o;
              break;
            }
          }
          const Record merged = buffers.merged(cell(x, y, z, 0));
          const Record source = buffers.levels(cell(x >> chosen, y >> chosen, z >> chosen, chosen));
          if (merged.mark() != static_cast<float>(chosen)) ++mismatches;
          for (int i = 0; i < 12; ++i) {
            const float expected = static_cast<float>(1 << chosen) * source.sh(i);
            if (std::abs(merged.sh(i) - expected) > 1e-6f * std::abs(expected)) ++mismatches;
          }
          worst_index = std::max(worst_index, chosen);
        }
      }
    }
    std::printf("k = %d: largest index %d, first level light crosses %d\n", k, worst_index,
                complete_level);
    EXPECT_EQ(mismatches, 0) << "k " << k << ": merged records differ from eq. 10";
    EXPECT_LE(worst_index, complete_level) << "k " << k;
  }
}

// The shells merge adds the levels, each in level-0 units (2^o times its value).
TEST_F(GpuTest, LpvOctreeShellsMergeAddsTheLevels) {
  RenderHarness harness(octree_setup(4, "shells", true));
  harness.render();
  const OctreeBuffers buffers(harness);
  ASSERT_TRUE(buffers.complete());
  int mismatches = 0;
  double coarse_share = 0.0, total = 0.0;
  for (int z = 0; z < kResolution; ++z) {
    for (int y = 0; y < kResolution; ++y) {
      for (int x = 0; x < kResolution; ++x) {
        const Record merged = buffers.merged(cell(x, y, z, 0));
        for (int i = 0; i < 12; ++i) {
          double expected = 0.0;
          for (int o = 0; o < kLevels; ++o) {
            const double v = (1 << o) * buffers.levels(cell(x >> o, y >> o, z >> o, o)).sh(i);
            expected += v;
            if (i == 4) {
              total += std::abs(v);
              if (o > 0) coarse_share += std::abs(v);
            }
          }
          if (std::abs(merged.sh(i) - expected) > 1e-5 * std::abs(expected) + 1e-9) ++mismatches;
        }
      }
    }
  }
  std::printf("shells merge: coarse levels carry %.2f of the green band-0 light\n",
              total > 0.0 ? coarse_share / total : 0.0);
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(coarse_share, 0.0) << "the coarse levels added nothing";
}

}  // namespace
}  // namespace voxgi::test
