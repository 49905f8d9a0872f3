#pragma once
// The bench report's "error against cost" tables: for each technique swept over one or two
// numeric settings, its approximation error (same-bounce indirect relMSE, net of the
// reference's own noise) laid out by setting, each rise over the cheaper neighbour marked, and
// the costliest configuration's error over the cheapest's. More voxels, cones or bounces should
// buy less error; the table shows where they do not instead of leaving it to the reader.

#include <optional>
#include <string>
#include <vector>

#include "apps/voxgi/bench_results.hpp"

namespace voxgi::cli {

// One cell: a configuration's approximation error.
struct ConvergenceCell {
  const ConfigResult* result = nullptr;  // null: the sweep has no such configuration
  double net = 0.0;                      // same-bounce relMSE minus the reference noise
  double raw = 0.0;                      // same-bounce relMSE as measured
};

// One technique's sweep: rows by the first swept setting, columns by the second (one column
// when only one setting is swept), values in numeric order.
struct ConvergenceGrid {
  std::string technique;
  std::string row_key, column_key;  // column_key empty for a one-setting sweep
  std::vector<std::string> rows, columns;
  std::vector<ConvergenceCell> cells;  // rows × columns, row-major

  const ConvergenceCell& at(size_t row, size_t column) const {
    return cells[row * columns.size() + column];
  }
};

// The grids of `results` (one group: same scene, camera and size): every technique whose
// configurations all have a same-bounce error and sweep the same one or two settings, each
// with numeric values, each combination once; techniques with a single configuration have no
// grid.
std::vector<ConvergenceGrid> convergence_grids(const std::vector<const ConfigResult*>& results);

// Relative rise of `higher_cost` over `lower_cost` (net errors), or nothing where either cell is
// missing or the error falls or stays equal.
std::optional<double> error_rise(const ConvergenceCell& lower_cost,
                                 const ConvergenceCell& higher_cost);

// The markdown section of the grids (nothing when there are none).
std::string convergence_markdown(const std::vector<ConvergenceGrid>& grids);

}  // namespace voxgi::cli
