#include "apps/voxgi/report_markdown.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <tuple>
#include <vector>

#include "apps/voxgi/report_charts.hpp"
#include "apps/voxgi/report_convergence.hpp"

namespace voxgi::cli {
namespace {

// Configurations compared in one chart: same scene, camera and resolution.
struct Group {
  std::string scene, camera;
  uint32_t width = 0, height = 0;
  std::vector<const ConfigResult*> results;
  std::string title() const {
    return scene + " / " + camera + " / " + std::to_string(width) + "x" + std::to_string(height);
  }
};

std::vector<Group> group_results(const BenchResults& results) {
  std::vector<Group> groups;
  for (const ConfigResult& r : results.results) {
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Group& g) {
      return g.scene == r.scene && g.camera == r.camera && g.width == r.width &&
             g.height == r.height;
    });
    if (it == groups.end()) {
      groups.push_back({r.scene, r.camera, r.width, r.height, {}});
      it = groups.end() - 1;
    }
    it->results.push_back(&r);
  }
  return groups;
}

std::string cell(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

std::string settings_of(const ConfigResult& r) {
  std::string text;
  for (const auto& [k, v] : r.overrides) text += (text.empty() ? "" : ", ") + k + "=" + v;
  return text.empty() ? "—" : text;
}

std::string metric_cell(const std::optional<image::ImageMetrics>& m,
                        double image::ImageMetrics::*field) {
  return m ? report_number((*m).*field) : "—";
}

// Small images are shown enlarged (and big ones reduced) to a common width.
std::string image_tag(const std::string& src, const std::string& alt, uint32_t width) {
  const uint32_t shown = width < 256 ? 256 : std::min<uint32_t>(width, 400);
  return "<img src=\"" + src + "\" alt=\"" + alt + "\" width=\"" + std::to_string(shown) + "\">";
}

std::string optional_cell(const std::optional<double>& value) {
  return value ? report_number(*value) : "—";
}

// The indirect light of graphs that declare their bounces: against the same-bounce reference,
// against the full reference, and what the full reference has beyond the same-bounce one.
void write_like_with_like_table(std::ostringstream& md, const Group& group) {
  md << "\n### Indirect light, like with like\n\n";
  md << "| id | technique | settings | bounces, BRDF | same-bounce bias | same-bounce relMSE | "
        "reference noise | same-bounce FLIP | full bias | full relMSE | full FLIP | missing |\n";
  md << "|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const ConfigResult* r : group.results) {
    if (!r->same_bounce) continue;
    const SameBounceResult& s = *r->same_bounce;
    md << "| " << r->id << " | " << cell(r->technique) << " | " << cell(settings_of(*r)) << " | "
       << s.bounces << ", " << s.brdf << (s.faces == "front" ? ", front faces" : "") << " | "
       << metric_cell(s.indirect, &image::ImageMetrics::luminance_bias) << " | "
       << metric_cell(s.indirect, &image::ImageMetrics::rel_mse) << " | "
       << optional_cell(s.reference_noise_rel_mse) << " | "
       << metric_cell(s.indirect, &image::ImageMetrics::hdr_flip) << " | "
       << metric_cell(s.full_indirect, &image::ImageMetrics::luminance_bias) << " | "
       << metric_cell(s.full_indirect, &image::ImageMetrics::rel_mse) << " | "
       << metric_cell(s.full_indirect, &image::ImageMetrics::hdr_flip) << " | "
       << optional_cell(s.missing_fraction) << " |\n";
  }
}

}  // namespace

std::string report_number(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

void write_report(const std::filesystem::path& dir, const BenchResults& results) {
  const std::vector<Group> groups = group_results(results);
  std::ostringstream md;
  md << "# Bench: " << results.name << "\n\n";
  md << "- bench file: `" << results.bench_file << "`\n";
  md << "- device: " << results.device << "\n";
  if (results.reference_frames == 0) {
    md << "- reference: image `" << results.reference_graph << "`\n";
  } else {
    md << "- reference: `" << results.reference_graph << "`, " << results.reference_frames
       << " frames\n";
  }
  if (results.changes == "lights") {
    md << "- measured frames: the lights change in each one, so every pass that depends on them "
          "runs again (the cost of a frame in which a light moves)\n";
  } else if (results.changes == "geometry") {
    md << "- measured frames: the geometry and the lights change in each one, so every pass "
          "that depends on the scene runs again\n";
  } else {
    md << "- measured frames: a static view (passes whose inputs did not change skip)\n";
  }
  md << "- configurations: " << results.results.size() << " of " << results.configurations_total;
  if (!results.shards.empty()) {
    md << " (merged from shards";
    for (const std::string& s : results.shards) md << " " << s;
    md << ")";
  }
  md << "\n";
  if (const std::vector<size_t> missing = results.missing(); !missing.empty()) {
    md << "- **incomplete**: no result for configuration(s)";
    for (size_t i : missing) md << " " << i;
    md << "\n";
  }
  md << "\nGPU times come from timestamps around each pass, over the measured frames after the "
        "warm-up; GPU MiB is the memory of the graph's resources (transients shared). Errors "
        "compare the linear image (and the `indirect` output, when both the "
        "graph and the reference have one) with the reference: relMSE is the mean of "
        "(a - b)^2 / (b^2 + 0.01), SSIM is on compressed luminance, FLIP is the mean HDR-FLIP "
        "(0: indistinguishable, 1: green against blue), bias is the relative difference of mean "
        "luminance (negative: too dark). Graphs that declare the bounces of their indirect light "
        "are also compared like with like: their `indirect` against the path tracer limited to "
        "the same bounces and BRDF terms (the approximation error), against the full reference "
        "(what a user sees), and the part of the full reference's indirect light the technique "
        "leaves out by design (missing = (full - same-bounce) / full mean luminance). A "
        "path-traced reference is itself noisy: reference noise is the part of the same-bounce "
        "relMSE that its noise adds (the mean of its per-pixel variance / (b^2 + 0.01)), the "
        "same for every configuration it serves; the error against the converged reference is "
        "the difference.\n\n";

  const std::filesystem::path charts = dir / "charts";
  std::filesystem::create_directories(charts);
  write_file_atomically(charts / "heat-scale.svg", heat_scale_svg(1e-4, 1.0));

  for (size_t g = 0; g < groups.size(); ++g) {
    const Group& group = groups[g];
    const std::string stem = "group" + std::to_string(g);
    md << "## " << group.title() << "\n\n";
    write_file_atomically(charts / (stem + "-error-vs-time.svg"),
                          error_vs_time_svg(group.results, ErrorMetric::RelMse,
                                            "Error against GPU time: " + group.title()));
    md << "![Error against GPU time](charts/" << stem << "-error-vs-time.svg)\n\n";
    const bool any_indirect = std::any_of(group.results.begin(), group.results.end(),
                                          [](const ConfigResult* r) { return r->indirect; });
    if (any_indirect) {
      write_file_atomically(charts / (stem + "-indirect-error-vs-time.svg"),
                            error_vs_time_svg(group.results, ErrorMetric::IndirectRelMse,
                                              "Indirect error against GPU time: " + group.title()));
      md << "![Indirect error against GPU time](charts/" << stem
         << "-indirect-error-vs-time.svg)\n\n";
    }
    const bool any_same_bounce = std::any_of(
        group.results.begin(), group.results.end(),
        [](const ConfigResult* r) { return r->same_bounce && r->same_bounce->indirect; });
    if (any_same_bounce) {
      write_file_atomically(
          charts / (stem + "-same-bounce-error-vs-time.svg"),
          error_vs_time_svg(group.results, ErrorMetric::SameBounceIndirectRelMse,
                            "Indirect error against the same-bounce reference: " + group.title()));
      md << "![Indirect error against the same-bounce reference](charts/" << stem
         << "-same-bounce-error-vs-time.svg)\n\n";
    }
    write_file_atomically(charts / (stem + "-pass-times.svg"),
                          pass_time_bars_svg(group.results, "GPU time per pass: " + group.title()));
    md << "![GPU time per pass](charts/" << stem << "-pass-times.svg)\n\n";

    md << "| id | technique | settings | GPU ms | p10–p90 | relMSE | RMSE | SSIM | FLIP | bias | "
          "indirect relMSE | non-finite | GPU MiB |\n";
    md << "|---|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const ConfigResult* r : group.results) {
      const Spread& t = r->times.gpu_total_ms;
      md << "| " << r->id << " | " << cell(r->technique) << " | " << cell(settings_of(*r)) << " | "
         << report_number(t.median) << " | " << report_number(t.p10) << "–" << report_number(t.p90)
         << " | " << metric_cell(r->full, &image::ImageMetrics::rel_mse) << " | "
         << metric_cell(r->full, &image::ImageMetrics::rmse) << " | "
         << metric_cell(r->full, &image::ImageMetrics::ssim_luminance) << " | "
         << metric_cell(r->full, &image::ImageMetrics::hdr_flip) << " | "
         << metric_cell(r->full, &image::ImageMetrics::luminance_bias) << " | "
         << metric_cell(r->indirect, &image::ImageMetrics::rel_mse) << " | "
         << (r->full ? std::to_string(r->full->non_finite_pixels) : "—") << " | "
         << (r->gpu_memory_bytes ? report_number(double(r->gpu_memory_bytes) / (1 << 20)) : "—")
         << " |\n";
    }
    if (std::any_of(group.results.begin(), group.results.end(),
                    [](const ConfigResult* r) { return r->same_bounce.has_value(); })) {
      write_like_with_like_table(md, group);
      md << convergence_markdown(convergence_grids(group.results));
    }
    md << "\n### Images\n\nReference, image and per-pixel relative error "
          "![heat map scale](charts/heat-scale.svg)\n\n";
    md << "| configuration | reference | image | error |\n|---|---|---|---|\n";
    for (const ConfigResult* r : group.results) {
      md << "| " << r->id << " " << cell(r->label) << "<br>relMSE "
         << metric_cell(r->full, &image::ImageMetrics::rel_mse) << ", "
         << report_number(r->times.gpu_total_ms.median) << " ms | "
         << image_tag(r->reference_png, "reference", r->width) << " | "
         << image_tag(r->image_png, r->id, r->width) << " | "
         << image_tag(r->heat_map_png, "error", r->width) << " |\n";
    }
    md << "\n";
  }
  write_file_atomically(dir / "report.md", md.str());
}

}  // namespace voxgi::cli
