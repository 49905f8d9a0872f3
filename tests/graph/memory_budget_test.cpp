#include <gtest/gtest.h>

#include <string>

#include "engine/graph/diagnostics.hpp"
#include "engine/graph/memory_budget.hpp"

namespace voxgi::graph {
namespace {

CompiledGraph graph_of(uint64_t big, uint64_t small) {
  CompiledGraph g;
  g.file = "graphs/big.json";
  CompiledResource a;
  a.info.name = "volume";
  a.loc = {"graphs/big.json", 7, 5};
  a.physical = 0;
  a.bytes = big;
  CompiledResource b;
  b.info.name = "image";
  b.loc = {"graphs/big.json", 9, 5};
  b.physical = 1;
  b.bytes = small;
  CompiledResource unused;  // culled: no allocation, not named
  unused.info.name = "unused";
  unused.bytes = big * 4;
  g.resources = {b, a, unused};
  g.total_bytes = big + small;
  return g;
}

TEST(MemoryBudget, AGraphLargerThanTheDeviceIsRefusedNamingItsLargestResources) {
  const CompiledGraph g = graph_of(3ull << 30, 1ull << 29);
  EXPECT_NO_THROW(check_memory_budget(g, 4ull << 30));
  EXPECT_NO_THROW(check_memory_budget(g, 0));  // unknown budget: no check
  try {
    check_memory_budget(g, 2ull << 30);
    ADD_FAILURE() << "no error";
  } catch (const GraphError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("graphs/big.json:7:5: error: field 'resources.volume'"), std::string::npos)
        << m;
    EXPECT_NE(m.find("needs 3.50 GiB of device memory, more than the device's 2.00 GiB"),
              std::string::npos)
        << m;
    EXPECT_NE(m.find("largest: volume 3.00 GiB, image 0.50 GiB"), std::string::npos) << m;
    EXPECT_EQ(m.find("unused"), std::string::npos) << m;
  }
}

}  // namespace
}  // namespace voxgi::graph
