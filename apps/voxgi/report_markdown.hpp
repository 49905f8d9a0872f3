#pragma once
// The bench report: report.md with SVG charts (charts/) and the images side by side with their
// error heat maps (images/), all relative to the output folder so the folder can be moved.

#include <filesystem>
#include <string>

#include "apps/voxgi/bench_results.hpp"

namespace voxgi::cli {

// The text of a number as the report's tables show it (4 significant digits).
std::string report_number(double value);

// Writes DIR/report.md and DIR/charts/*.svg from `results` (images must already be in DIR).
void write_report(const std::filesystem::path& dir, const BenchResults& results);

}  // namespace voxgi::cli
