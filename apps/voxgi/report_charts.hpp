#pragma once
// SVG charts of bench results, written without any library: error against GPU time with each
// technique's Pareto front, per-pass stacked time bars, and the heat map's colour scale.

#include <string>
#include <vector>

#include "apps/voxgi/bench_results.hpp"

namespace voxgi::cli {

// Which error a chart plots: relMSE of the linear image or of `indirect` against the reference,
// or of `indirect` against the same-bounce reference (the approximation error alone).
enum class ErrorMetric { RelMse, IndirectRelMse, SameBounceIndirectRelMse };

// One point per configuration with that metric: x the median GPU time (whiskers p10..p90),
// y the error on a log axis; one colour per technique and its Pareto front (no other point of
// the technique is both faster and more accurate) drawn as a line.
std::string error_vs_time_svg(const std::vector<const ConfigResult*>& results, ErrorMetric metric,
                              const std::string& title);

// One horizontal bar per configuration: each pass's median share of the frame stacked, the
// median frame total written at the end.
std::string pass_time_bars_svg(const std::vector<const ConfigResult*>& results,
                               const std::string& title);

// The heat map's ramp with its logarithmic labels.
std::string heat_scale_svg(double low, double high);

// The Pareto-optimal points among (time, error) pairs: indices sorted by time, each with a
// lower error than every faster one. Non-finite errors never qualify.
std::vector<size_t> pareto_front(const std::vector<double>& times,
                                 const std::vector<double>& errors);

}  // namespace voxgi::cli
