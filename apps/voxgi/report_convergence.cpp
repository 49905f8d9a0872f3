#include "apps/voxgi/report_convergence.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <map>
#include <sstream>

#include "apps/voxgi/report_markdown.hpp"

namespace voxgi::cli {
namespace {

// A swept value as a number (as the command line writes it, whatever the locale); nothing for
// text or a non-finite value.
std::optional<double> numeric(const std::string& text) {
  double value = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || !std::isfinite(value)) return std::nullopt;
  return value;
}

// The distinct values of `key` among `results`, in numeric order; empty when one is not a number.
std::vector<std::string> sorted_values(const std::vector<const ConfigResult*>& results,
                                       const std::string& key) {
  std::vector<std::pair<double, std::string>> values;
  for (const ConfigResult* r : results) {
    const std::string& text = r->swept.at(key);
    const std::optional<double> value = numeric(text);
    if (!value) return {};
    if (std::none_of(values.begin(), values.end(), [&](const auto& v) { return v.second == text; }))
      values.emplace_back(*value, text);
  }
  std::sort(values.begin(), values.end());
  std::vector<std::string> out;
  for (const auto& v : values) out.push_back(v.second);
  return out;
}

std::optional<ConvergenceGrid> grid_of(const std::string& technique,
                                       const std::vector<const ConfigResult*>& results) {
  if (results.size() < 2) return std::nullopt;
  const std::map<std::string, std::string>& first = results.front()->swept;
  if (first.empty() || first.size() > 2) return std::nullopt;
  for (const ConfigResult* r : results) {
    if (!r->same_bounce || !r->same_bounce->indirect) return std::nullopt;
    if (r->swept.size() != first.size()) return std::nullopt;
    for (const auto& entry : first) {
      if (!r->swept.count(entry.first)) return std::nullopt;
    }
  }
  ConvergenceGrid grid;
  grid.technique = technique;
  grid.row_key = first.begin()->first;
  grid.rows = sorted_values(results, grid.row_key);
  if (grid.rows.empty()) return std::nullopt;
  if (first.size() == 2) {
    grid.column_key = std::next(first.begin())->first;
    grid.columns = sorted_values(results, grid.column_key);
    if (grid.columns.empty()) return std::nullopt;
  } else {
    grid.columns = {""};
  }
  grid.cells.resize(grid.rows.size() * grid.columns.size());
  for (const ConfigResult* r : results) {
    const size_t row = static_cast<size_t>(
        std::find(grid.rows.begin(), grid.rows.end(), r->swept.at(grid.row_key)) -
        grid.rows.begin());
    size_t column = 0;
    if (!grid.column_key.empty()) {
      column = static_cast<size_t>(
          std::find(grid.columns.begin(), grid.columns.end(), r->swept.at(grid.column_key)) -
          grid.columns.begin());
    }
    ConvergenceCell& c = grid.cells[row * grid.columns.size() + column];
    // Two entries of one label that differ only in what they set are not one sweep.
    if (c.result) return std::nullopt;
    const SameBounceResult& s = *r->same_bounce;
    c.result = r;
    c.raw = s.indirect->rel_mse;
    c.net = c.raw - s.reference_noise_rel_mse.value_or(0.0);
  }
  return grid;
}

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "+%.1f%%", 100.0 * fraction);
  return text;
}

}  // namespace

std::vector<ConvergenceGrid> convergence_grids(const std::vector<const ConfigResult*>& results) {
  std::vector<std::string> techniques;
  for (const ConfigResult* r : results) {
    if (std::find(techniques.begin(), techniques.end(), r->technique) == techniques.end())
      techniques.push_back(r->technique);
  }
  std::vector<ConvergenceGrid> grids;
  for (const std::string& technique : techniques) {
    std::vector<const ConfigResult*> own;
    for (const ConfigResult* r : results) {
      if (r->technique == technique) own.push_back(r);
    }
    if (std::optional<ConvergenceGrid> grid = grid_of(technique, own)) grids.push_back(*grid);
  }
  return grids;
}

std::optional<double> error_rise(const ConvergenceCell& lower_cost,
                                 const ConvergenceCell& higher_cost) {
  if (!lower_cost.result || !higher_cost.result || !(higher_cost.net > lower_cost.net))
    return std::nullopt;
  if (!(lower_cost.net > 0.0)) return std::nullopt;  // no relative rise over nothing
  return higher_cost.net / lower_cost.net - 1.0;
}

std::string convergence_markdown(const std::vector<ConvergenceGrid>& grids) {
  if (grids.empty()) return {};
  std::ostringstream md;
  md << "\n### Error against cost\n\n"
        "The same-bounce indirect relMSE net of the reference's noise (the approximation error "
        "against the converged same-bounce reference), by setting. ↑ marks a configuration "
        "whose error is higher than that of the cheaper one before it in its row or column, by "
        "how much: more voxels or cones should buy less error, so such a mark is a defect to "
        "explain (or, within a few percent, the reference's noise, which does not cancel "
        "exactly in a difference). Each bounce count has its own reference, with more light to "
        "get right; a rise there says the added bounces are less accurate than the first. "
        "Below each table, the costliest configuration's error over the cheapest's (with the "
        "noise left in).\n";
  for (const ConvergenceGrid& grid : grids) {
    md << "\n**" << grid.technique << "**";
    if (!grid.column_key.empty()) md << " (rows `" << grid.row_key << "`)";
    md << "\n\n| `" << (grid.column_key.empty() ? grid.row_key : grid.column_key) << "` |";
    if (grid.column_key.empty()) {
      md << " error |\n|---|---:|\n";
    } else {
      for (const std::string& c : grid.columns) md << " " << c << " |";
      md << "\n|---|";
      for (size_t c = 0; c < grid.columns.size(); ++c) md << "---:|";
      md << "\n";
    }
    for (size_t row = 0; row < grid.rows.size(); ++row) {
      md << "| " << grid.rows[row] << " |";
      for (size_t column = 0; column < grid.columns.size(); ++column) {
        const ConvergenceCell& cell = grid.at(row, column);
        if (!cell.result) {
          md << " — |";
          continue;
        }
        md << " " << report_number(cell.net);
        if (column > 0) {
          if (std::optional<double> rise = error_rise(grid.at(row, column - 1), cell))
            md << " ↑ " << percent(*rise) << " over " << grid.columns[column - 1];
        }
        if (row > 0) {
          if (std::optional<double> rise = error_rise(grid.at(row - 1, column), cell))
            md << " ↑ " << percent(*rise) << " over " << grid.rows[row - 1];
        }
        md << " |";
      }
      md << "\n";
    }
    const ConvergenceCell& cheapest = grid.cells.front();
    const ConvergenceCell& costliest = grid.cells.back();
    if (cheapest.result && costliest.result && cheapest.net > 0.0 && cheapest.raw > 0.0) {
      md << "\nCostliest over cheapest (" << costliest.result->id << " over " << cheapest.result->id
         << "): " << report_number(costliest.net / cheapest.net) << " ("
         << report_number(costliest.raw / cheapest.raw) << " with the noise)\n";
    }
  }
  return md.str();
}

}  // namespace voxgi::cli
