#include "apps/voxgi/report_charts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>

#include "engine/image/error_map.hpp"

namespace voxgi::cli {
namespace {

// Distinguishable colours (also for common colour-vision deficiencies), cycled.
constexpr const char* kPalette[] = {"#0072b2", "#e69f00", "#009e73", "#d55e00", "#cc79a7",
                                    "#56b4e9", "#f0e442", "#000000", "#999999", "#882255"};
constexpr size_t kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

// The palette's colours first, then hues a golden angle apart, so that many passes still get
// colours of their own.
std::string colour_of(size_t index) {
  if (index < kPaletteSize) return kPalette[index];
  const double hue = std::fmod(static_cast<double>(index - kPaletteSize) * 137.508 + 20.0, 360.0);
  // HSL (s = 0.6, l = 0.5) to RGB.
  const double c = 0.6, x = c * (1.0 - std::fabs(std::fmod(hue / 60.0, 2.0) - 1.0)), m = 0.2;
  double r = 0, g = 0, b = 0;
  switch (static_cast<int>(hue / 60.0)) {
    case 0:
      r = c;
      g = x;
      break;
    case 1:
      r = x;
      g = c;
      break;
    case 2:
      g = c;
      b = x;
      break;
    case 3:
      g = x;
      b = c;
      break;
    case 4:
      r = x;
      b = c;
      break;
    default:
      r = c;
      b = x;
      break;
  }
  char text[16];
  std::snprintf(text, sizeof text, "#%02x%02x%02x", int((r + m) * 255 + 0.5),
                int((g + m) * 255 + 0.5), int((b + m) * 255 + 0.5));
  return text;
}

// The last part of a parameter key: "cone_trace.diffuse_cones" -> "diffuse_cones".
std::string short_key(const std::string& key) {
  const size_t dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string num(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", v);
  return text;
}

std::string tick_label(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

class Svg {
 public:
  Svg(double width, double height) {
    out_ << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\""
         << num(height) << "\" viewBox=\"0 0 " << num(width) << " " << num(height)
         << "\" font-family=\"sans-serif\" font-size=\"12\">\n"
         << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  }
  void line(double x1, double y1, double x2, double y2, const std::string& stroke,
            double width = 1.0, const std::string& extra = "") {
    out_ << "<line x1=\"" << num(x1) << "\" y1=\"" << num(y1) << "\" x2=\"" << num(x2) << "\" y2=\""
         << num(y2) << "\" stroke=\"" << stroke << "\" stroke-width=\"" << num(width) << "\" "
         << extra << "/>\n";
  }
  void rect(double x, double y, double w, double h, const std::string& fill,
            const std::string& tooltip = "") {
    out_ << "<rect x=\"" << num(x) << "\" y=\"" << num(y) << "\" width=\"" << num(std::max(w, 0.0))
         << "\" height=\"" << num(h) << "\" fill=\"" << fill << "\">";
    if (!tooltip.empty()) out_ << "<title>" << escape(tooltip) << "</title>";
    out_ << "</rect>\n";
  }
  void circle(double x, double y, double r, const std::string& fill, const std::string& tooltip) {
    out_ << "<circle cx=\"" << num(x) << "\" cy=\"" << num(y) << "\" r=\"" << num(r) << "\" fill=\""
         << fill << "\" stroke=\"white\" stroke-width=\"1\"><title>" << escape(tooltip)
         << "</title></circle>\n";
  }
  void text(double x, double y, const std::string& content, const std::string& anchor = "start",
            const std::string& extra = "") {
    out_ << "<text x=\"" << num(x) << "\" y=\"" << num(y) << "\" text-anchor=\"" << anchor << "\" "
         << extra << ">" << escape(content) << "</text>\n";
  }
  void polyline(const std::vector<std::pair<double, double>>& points, const std::string& stroke) {
    out_ << "<polyline fill=\"none\" stroke=\"" << stroke << "\" stroke-width=\"2\" points=\"";
    for (const auto& [x, y] : points) out_ << num(x) << "," << num(y) << " ";
    out_ << "\"/>\n";
  }
  std::string finish() {
    out_ << "</svg>\n";
    return out_.str();
  }

 private:
  std::ostringstream out_;
};

// "Nice" linear ticks (1, 2, 5 × 10^k steps) covering [lo, hi].
std::vector<double> linear_ticks(double lo, double hi) {
  const double span = std::max(hi - lo, 1e-12);
  const double rough = span / 5.0;
  const double magnitude = std::pow(10.0, std::floor(std::log10(rough)));
  double step = magnitude;
  for (double m : {1.0, 2.0, 5.0, 10.0}) {
    if (m * magnitude >= rough) {
      step = m * magnitude;
      break;
    }
  }
  // The last tick is at or beyond `hi`, so that the axis covers every value.
  std::vector<double> ticks;
  for (double t = std::floor(lo / step) * step;; t += step) {
    ticks.push_back(std::fabs(t) < step * 1e-9 ? 0.0 : t);
    if (t >= hi - step * 1e-9) break;
  }
  return ticks;
}

std::string metric_name(ErrorMetric metric) {
  switch (metric) {
    case ErrorMetric::RelMse:
      return "relMSE (full image)";
    case ErrorMetric::IndirectRelMse:
      return "relMSE (indirect)";
    case ErrorMetric::SameBounceIndirectRelMse:
      return "relMSE (indirect, same-bounce reference)";
  }
  return {};
}

std::optional<double> metric_of(const ConfigResult& r, ErrorMetric metric) {
  const std::optional<image::ImageMetrics>* m = &r.full;
  if (metric == ErrorMetric::IndirectRelMse) m = &r.indirect;
  if (metric == ErrorMetric::SameBounceIndirectRelMse) {
    if (!r.same_bounce) return std::nullopt;
    m = &r.same_bounce->indirect;
  }
  if (!*m) return std::nullopt;
  return (*m)->rel_mse;
}

}  // namespace

std::vector<size_t> pareto_front(const std::vector<double>& times,
                                 const std::vector<double>& errors) {
  std::vector<size_t> order(times.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return times[a] != times[b] ? times[a] < times[b] : errors[a] < errors[b];
  });
  std::vector<size_t> front;
  double best = std::numeric_limits<double>::infinity();
  for (size_t i : order) {
    if (std::isfinite(errors[i]) && errors[i] < best) {
      front.push_back(i);
      best = errors[i];
    }
  }
  return front;
}

std::string error_vs_time_svg(const std::vector<const ConfigResult*>& results, ErrorMetric metric,
                              const std::string& title) {
  constexpr double kWidth = 720, kHeight = 440, kLeft = 80, kRight = 180, kTop = 40, kBottom = 56;
  const double plot_w = kWidth - kLeft - kRight, plot_h = kHeight - kTop - kBottom;
  Svg svg(kWidth, kHeight);
  svg.text(kWidth / 2, 22, title, "middle", "font-size=\"15\" font-weight=\"bold\"");

  struct Point {
    const ConfigResult* r;
    double time, p10, p90, error;
  };
  std::map<std::string, std::vector<Point>> by_technique;
  std::vector<std::string> techniques;
  double t_max = 0.0, e_min = std::numeric_limits<double>::infinity(), e_max = 0.0;
  for (const ConfigResult* r : results) {
    const std::optional<double> error = metric_of(*r, metric);
    if (!error || !std::isfinite(*error)) continue;
    // Zero error would sit at -infinity on a log axis; it is drawn at the axis floor.
    const double e = std::max(*error, 1e-8);
    if (!by_technique.count(r->technique)) techniques.push_back(r->technique);
    const Spread& t = r->times.gpu_total_ms;
    by_technique[r->technique].push_back({r, t.median, t.p10, t.p90, e});
    t_max = std::max(t_max, t.p90);
    e_min = std::min(e_min, e);
    e_max = std::max(e_max, e);
  }
  if (techniques.empty()) {
    svg.text(kWidth / 2, kHeight / 2, "no configuration has this metric", "middle");
    return svg.finish();
  }
  const std::vector<double> x_ticks = linear_ticks(0.0, t_max > 0.0 ? t_max * 1.05 : 1.0);
  const double x_hi = x_ticks.back() > 0.0 ? x_ticks.back() : 1.0;
  const double y_lo = std::pow(10.0, std::floor(std::log10(e_min)));
  double y_hi = std::pow(10.0, std::ceil(std::log10(e_max)));
  if (y_hi <= y_lo) y_hi = y_lo * 10.0;
  auto x_of = [&](double t) { return kLeft + t / x_hi * plot_w; };
  auto y_of = [&](double e) {
    return kTop + plot_h * (1.0 - (std::log10(e) - std::log10(y_lo)) /
                                      (std::log10(y_hi) - std::log10(y_lo)));
  };

  for (double t : x_ticks) {
    svg.line(x_of(t), kTop, x_of(t), kTop + plot_h, "#e4e4e4");
    svg.text(x_of(t), kTop + plot_h + 16, tick_label(t), "middle");
  }
  // Decades, and 2× and 5× between them when there are few decades to label.
  const bool minor = std::log10(y_hi) - std::log10(y_lo) <= 2.0 + 1e-9;
  for (double e = y_lo; e <= y_hi * 1.0001; e *= 10.0) {
    svg.line(kLeft, y_of(e), kLeft + plot_w, y_of(e), "#e4e4e4");
    svg.text(kLeft - 6, y_of(e) + 4, tick_label(e), "end");
    for (double m : {2.0, 5.0}) {
      if (!minor || e * m > y_hi * 1.0001) continue;
      svg.line(kLeft, y_of(e * m), kLeft + plot_w, y_of(e * m), "#f2f2f2");
      svg.text(kLeft - 6, y_of(e * m) + 4, tick_label(e * m), "end", "fill=\"#777\"");
    }
  }
  svg.line(kLeft, kTop + plot_h, kLeft + plot_w, kTop + plot_h, "#333");
  svg.line(kLeft, kTop, kLeft, kTop + plot_h, "#333");
  svg.text(kLeft + plot_w / 2, kHeight - 14, "GPU time per frame, ms (median; whiskers p10-p90)",
           "middle");
  svg.text(18, kTop + plot_h / 2, metric_name(metric) + ", log scale", "middle",
           "transform=\"rotate(-90 18 " + num(kTop + plot_h / 2) + ")\"");

  for (size_t k = 0; k < techniques.size(); ++k) {
    const std::string colour = colour_of(k);
    const std::vector<Point>& points = by_technique[techniques[k]];
    std::vector<double> times, errors;
    for (const Point& p : points) {
      times.push_back(p.time);
      errors.push_back(p.error);
    }
    std::vector<std::pair<double, double>> front;
    for (size_t i : pareto_front(times, errors)) {
      front.emplace_back(x_of(points[i].time), y_of(points[i].error));
    }
    if (front.size() > 1) svg.polyline(front, colour);
    for (const Point& p : points) {
      svg.line(x_of(p.p10), y_of(p.error), x_of(p.p90), y_of(p.error), colour, 1.0,
               "opacity=\"0.6\"");
      char tip[512];
      std::snprintf(tip, sizeof tip, "%s %s: %.4g ms, %s %.4g", p.r->id.c_str(), p.r->label.c_str(),
                    p.time, metric_name(metric).c_str(), p.error);
      svg.circle(x_of(p.time), y_of(p.error), 5, colour, tip);
      std::string settings;
      for (const auto& [key, value] : p.r->swept) settings += (settings.empty() ? "" : " ") + value;
      if (!settings.empty()) {
        svg.text(x_of(p.time) + 7, y_of(p.error) - 6, settings, "start",
                 "font-size=\"9\" fill=\"#555\"");
      }
    }
    // The legend names what the numbers next to the technique's points are.
    const double ly = kTop + 10 + 34.0 * static_cast<double>(k);
    svg.circle(kLeft + plot_w + 20, ly, 5, colour, techniques[k]);
    svg.text(kLeft + plot_w + 32, ly + 4, techniques[k]);
    std::string keys;
    for (const auto& [key, value] : points.front().r->swept) {
      keys += (keys.empty() ? "" : ", ") + short_key(key);
    }
    if (!keys.empty()) {
      svg.text(kLeft + plot_w + 32, ly + 18, keys, "start", "font-size=\"9\" fill=\"#555\"");
    }
  }
  svg.text(kLeft + plot_w + 14, kTop + 20 + 34.0 * static_cast<double>(techniques.size()),
           "lines: Pareto fronts", "start", "font-size=\"10\" fill=\"#555\"");
  return svg.finish();
}

std::string pass_time_bars_svg(const std::vector<const ConfigResult*>& results,
                               const std::string& title) {
  constexpr double kRight = 170, kTop = 40, kBar = 18, kGap = 8, kPlotWidth = 480;
  constexpr double kTotalRoom = 90;  // for "total 123 ms" after the longest bar
  // Room for the longest label (about 6.6 px per character at 12 px).
  size_t longest = 0;
  for (const ConfigResult* r : results)
    longest = std::max(longest, (r->id + " " + r->label).size());
  const double kLeft = std::min(16.0 + 6.6 * static_cast<double>(longest), 480.0);
  const double plot_w = kPlotWidth, kWidth = kLeft + plot_w + kTotalRoom + kRight;
  // Passes of the same name share a colour across bars.
  std::vector<std::string> pass_names;
  double total_max = 0.0;
  for (const ConfigResult* r : results) {
    double total = 0.0;
    for (const PassTime& p : r->times.passes) {
      if (std::find(pass_names.begin(), pass_names.end(), p.pass) == pass_names.end()) {
        pass_names.push_back(p.pass);
      }
      total += p.share_ms;
    }
    total_max = std::max({total_max, total, r->times.gpu_total_ms.median});
  }
  const double legend_h = 20.0 * static_cast<double>(pass_names.size()) + 10;
  const double bars_h = (kBar + kGap) * static_cast<double>(results.size());
  const double height = kTop + std::max(bars_h, legend_h) + 50;
  Svg svg(kWidth, height);
  svg.text(kWidth / 2, 22, title, "middle", "font-size=\"15\" font-weight=\"bold\"");
  const std::vector<double> ticks = linear_ticks(0.0, total_max > 0.0 ? total_max * 1.02 : 1.0);
  const double x_hi = ticks.back() > 0.0 ? ticks.back() : 1.0;
  auto x_of = [&](double ms) { return kLeft + ms / x_hi * plot_w; };
  const double axis_y = kTop + bars_h + 4;
  for (double t : ticks) {
    svg.line(x_of(t), kTop - 4, x_of(t), axis_y, "#e4e4e4");
    svg.text(x_of(t), axis_y + 16, tick_label(t), "middle");
  }
  svg.text(kLeft + plot_w / 2, axis_y + 36,
           "GPU ms per frame: median of each pass (skipped frames count 0); total: median frame",
           "middle");
  for (size_t i = 0; i < results.size(); ++i) {
    const ConfigResult& r = *results[i];
    const double y = kTop + static_cast<double>(i) * (kBar + kGap);
    std::string name = r.id + " " + r.label;
    if (name.size() > 72) name = name.substr(0, 71) + "…";
    svg.text(kLeft - 8, y + kBar - 5, name, "end");
    double x = 0.0;
    for (const PassTime& p : r.times.passes) {
      const size_t colour = static_cast<size_t>(
          std::find(pass_names.begin(), pass_names.end(), p.pass) - pass_names.begin());
      char tip[256];
      std::snprintf(tip, sizeof tip, "%s (%s): %.4g ms median%s", p.pass.c_str(), p.type.c_str(),
                    p.share_ms, p.skipped ? ", skipped in some frames" : "");
      svg.rect(x_of(x), y, x_of(x + p.share_ms) - x_of(x), kBar, colour_of(colour), tip);
      x += p.share_ms;
    }
    char total[64];
    std::snprintf(total, sizeof total, "total %.3g ms", r.times.gpu_total_ms.median);
    svg.text(x_of(x) + 4, y + kBar - 5, total, "start", "font-size=\"10\"");
  }
  for (size_t k = 0; k < pass_names.size(); ++k) {
    const double ly = kTop + 20.0 * static_cast<double>(k);
    svg.rect(kLeft + plot_w + kTotalRoom + 10, ly, 12, 12, colour_of(k));
    svg.text(kLeft + plot_w + kTotalRoom + 28, ly + 10, pass_names[k]);
  }
  return svg.finish();
}

std::string heat_scale_svg(double low, double high) {
  constexpr double kWidth = 420, kHeight = 56, kLeft = 20, kBarW = 380;
  Svg svg(kWidth, kHeight);
  constexpr int kSteps = 64;
  for (int i = 0; i < kSteps; ++i) {
    float rgb[3];
    image::heat_map_colour((i + 0.5) / kSteps, rgb);
    char colour[16];
    std::snprintf(colour, sizeof colour, "#%02x%02x%02x", int(rgb[0] * 255 + 0.5),
                  int(rgb[1] * 255 + 0.5), int(rgb[2] * 255 + 0.5));
    svg.rect(kLeft + kBarW * i / kSteps, 8, kBarW / kSteps + 0.5, 18, colour);
  }
  const double decades = std::log10(high) - std::log10(low);
  for (double e = low; e <= high * 1.0001; e *= 10.0) {
    const double x = kLeft + kBarW * (std::log10(e) - std::log10(low)) / decades;
    svg.line(x, 26, x, 31, "#333");
    svg.text(x, 44, tick_label(e), "middle", "font-size=\"10\"");
  }
  svg.text(kLeft + kBarW, 54, "per-pixel relative squared error", "end", "font-size=\"9\"");
  return svg.finish();
}

}  // namespace voxgi::cli
