#include "apps/voxgi/bench_results.hpp"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>
#include <stdexcept>

#include "engine/runtime/timings.hpp"

namespace voxgi::cli {
namespace {

using nlohmann::json;

using runtime::percentile;

json spread_json(const Spread& s) {
  return {{"median", s.median}, {"min", s.min}, {"max", s.max}, {"p10", s.p10}, {"p90", s.p90}};
}

json metrics_json(const std::optional<image::ImageMetrics>& m);

json same_bounce_json(const std::optional<SameBounceResult>& s) {
  if (!s) return nullptr;
  return {{"bounces", s->bounces},
          {"brdf", s->brdf},
          {"faces", s->faces},
          {"reference_set", s->reference_set},
          {"reference_key", s->reference_key},
          {"reference_cache_hit", s->reference_cache_hit},
          {"indirect", metrics_json(s->indirect)},
          {"full_indirect", metrics_json(s->full_indirect)},
          {"full_reference_key", s->full_reference_key},
          {"missing_fraction", s->missing_fraction ? json(*s->missing_fraction) : json(nullptr)},
          {"reference_noise_rel_mse",
           s->reference_noise_rel_mse ? json(*s->reference_noise_rel_mse) : json(nullptr)}};
}

json metrics_json(const std::optional<image::ImageMetrics>& m) {
  if (!m) return nullptr;
  return {{"rel_mse", m->rel_mse},
          {"rmse", m->rmse},
          {"ssim_luminance", m->ssim_luminance},
          {"hdr_flip", m->hdr_flip},
          {"luminance_bias", m->luminance_bias},
          {"mean_luminance", m->mean_luminance},
          {"mean_luminance_reference", m->mean_luminance_reference},
          {"non_finite_pixels", m->non_finite_pixels},
          {"non_finite_reference_pixels", m->non_finite_reference_pixels},
          {"compared_pixels", m->compared_pixels}};
}

// Reads fields with errors that say which file and field is wrong.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}

  const json& at(const json& object, const std::string& key, const std::string& where) const {
    if (!object.is_object() || !object.contains(key)) fail(where + key, "missing");
    return object.at(key);
  }
  std::string text(const json& object, const std::string& key, const std::string& where) const {
    const json& v = at(object, key, where);
    if (!v.is_string()) fail(where + key, "expected a string");
    return v.get<std::string>();
  }
  double number(const json& object, const std::string& key, const std::string& where) const {
    const json& v = at(object, key, where);
    if (!v.is_number()) fail(where + key, "expected a number");
    return v.get<double>();
  }
  uint64_t count(const json& object, const std::string& key, const std::string& where) const {
    const double n = number(object, key, where);
    if (n < 0 || n != std::floor(n)) fail(where + key, "expected a non-negative integer");
    return static_cast<uint64_t>(n);
  }
  bool flag(const json& object, const std::string& key, const std::string& where) const {
    const json& v = at(object, key, where);
    if (!v.is_boolean()) fail(where + key, "expected true or false");
    return v.get<bool>();
  }
  std::map<std::string, std::string> strings(const json& object, const std::string& key,
                                             const std::string& where) const {
    const json& v = at(object, key, where);
    if (!v.is_object()) fail(where + key, "expected an object of strings");
    std::map<std::string, std::string> result;
    for (const auto& [k, value] : v.items()) {
      if (!value.is_string()) fail(where + key + "." + k, "expected a string");
      result[k] = value.get<std::string>();
    }
    return result;
  }
  Spread spread(const json& object, const std::string& key, const std::string& where) const {
    const json& v = at(object, key, where);
    const std::string inner = where + key + ".";
    return {number(v, "median", inner), number(v, "min", inner), number(v, "max", inner),
            number(v, "p10", inner), number(v, "p90", inner)};
  }
  std::optional<image::ImageMetrics> metrics(const json& object, const std::string& key,
                                             const std::string& where) const {
    const json& v = at(object, key, where);
    if (v.is_null()) return std::nullopt;
    const std::string inner = where + key + ".";
    image::ImageMetrics m;
    m.rel_mse = number(v, "rel_mse", inner);
    m.rmse = number(v, "rmse", inner);
    m.ssim_luminance = number(v, "ssim_luminance", inner);
    // Absent from results written before HDR-FLIP was measured.
    if (v.contains("hdr_flip")) m.hdr_flip = number(v, "hdr_flip", inner);
    m.luminance_bias = number(v, "luminance_bias", inner);
    m.mean_luminance = number(v, "mean_luminance", inner);
    m.mean_luminance_reference = number(v, "mean_luminance_reference", inner);
    m.non_finite_pixels = count(v, "non_finite_pixels", inner);
    m.non_finite_reference_pixels = count(v, "non_finite_reference_pixels", inner);
    m.compared_pixels = count(v, "compared_pixels", inner);
    return m;
  }
  // Absent (results written before same-bounce references) or null: none.
  std::optional<SameBounceResult> same_bounce(const json& object, const std::string& key,
                                              const std::string& where) const {
    if (!object.contains(key) || object.at(key).is_null()) return std::nullopt;
    const json& v = object.at(key);
    const std::string inner = where + key + ".";
    SameBounceResult s;
    s.bounces = static_cast<uint32_t>(count(v, "bounces", inner));
    s.brdf = text(v, "brdf", inner);
    // Absent in results written before graphs declared their faces: both, as then.
    if (v.contains("faces")) s.faces = text(v, "faces", inner);
    s.reference_set = strings(v, "reference_set", inner);
    s.reference_key = text(v, "reference_key", inner);
    s.reference_cache_hit = flag(v, "reference_cache_hit", inner);
    s.indirect = metrics(v, "indirect", inner);
    s.full_indirect = metrics(v, "full_indirect", inner);
    s.full_reference_key = text(v, "full_reference_key", inner);
    if (!at(v, "missing_fraction", inner).is_null()) {
      s.missing_fraction = number(v, "missing_fraction", inner);
    }
    // Absent in results written before references carried their variance.
    if (v.contains("reference_noise_rel_mse") && !v.at("reference_noise_rel_mse").is_null()) {
      s.reference_noise_rel_mse = number(v, "reference_noise_rel_mse", inner);
    }
    return s;
  }
  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw std::runtime_error(file_ + ": field '" + field + "': " + message);
  }

 private:
  std::string file_;
};

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

std::string number_text(double value) {
  char text[64];
  std::snprintf(text, sizeof text, "%.9g", value);
  return text;
}

}  // namespace

Spread spread_of(std::vector<double> values) {
  Spread s;
  if (values.empty()) return s;
  std::sort(values.begin(), values.end());
  s.min = values.front();
  s.max = values.back();
  s.median = percentile(values, 0.5);
  s.p10 = percentile(values, 0.1);
  s.p90 = percentile(values, 0.9);
  return s;
}

FrameTimes summarize_frames(const std::vector<std::vector<graph::Executor::PassTiming>>& frames) {
  FrameTimes result;
  std::map<std::string, size_t> index;
  std::vector<std::vector<double>> ran, shares;
  std::vector<double> totals, cpu_totals;
  for (const auto& frame : frames) {
    double total = 0.0, cpu = 0.0;
    for (const graph::Executor::PassTiming& t : frame) {
      auto [it, inserted] = index.try_emplace(t.pass, result.passes.size());
      if (inserted) {
        PassTime pass;
        pass.pass = t.pass;
        pass.type = t.type;
        result.passes.push_back(pass);
        ran.emplace_back();
        shares.emplace_back();
      }
      PassTime& pass = result.passes[it->second];
      cpu += t.cpu_ms;
      if (!t.skipped.empty()) {
        ++pass.skipped;
        pass.skip_reason = t.skipped;
        shares[it->second].push_back(0.0);
        continue;
      }
      ++pass.frames;
      ran[it->second].push_back(t.gpu_ms);
      shares[it->second].push_back(t.gpu_ms);
      total += t.gpu_ms;
    }
    totals.push_back(total);
    cpu_totals.push_back(cpu);
  }
  for (size_t i = 0; i < result.passes.size(); ++i) {
    result.passes[i].gpu_ms = spread_of(ran[i]);
    result.passes[i].share_ms = spread_of(shares[i]).median;
  }
  result.gpu_total_ms = spread_of(totals);
  result.cpu_total_ms = spread_of(cpu_totals);
  return result;
}

std::vector<size_t> BenchResults::missing() const {
  std::set<size_t> present;
  for (const ConfigResult& r : results) present.insert(r.index);
  std::vector<size_t> result;
  for (size_t i = 0; i < configurations_total; ++i) {
    if (!present.count(i)) result.push_back(i);
  }
  return result;
}

json to_json(const BenchResults& results) {
  json doc;
  doc["format"] = "voxgi-bench-results-1";
  doc["name"] = results.name;
  doc["bench_file"] = results.bench_file;
  doc["bench_hash"] = results.bench_hash;
  doc["device"] = results.device;
  doc["reference"] = {{"graph", results.reference_graph}, {"frames", results.reference_frames}};
  doc["changes"] = results.changes;
  doc["configurations_total"] = results.configurations_total;
  doc["shards"] = results.shards;
  doc["missing"] = results.missing();
  doc["statistics"] =
      "GPU times from timestamps over the measured frames (after the warm-up): median, min, max, "
      "p10, p90; a frame's total sums its passes, a skipped pass counting 0 ms";
  json list = json::array();
  for (const ConfigResult& r : results.results) {
    json passes = json::array();
    for (const PassTime& p : r.times.passes) {
      passes.push_back({{"pass", p.pass},
                        {"type", p.type},
                        {"gpu_ms", spread_json(p.gpu_ms)},
                        {"share_ms", p.share_ms},
                        {"frames", p.frames},
                        {"skipped_frames", p.skipped},
                        {"skip_reason", p.skip_reason}});
    }
    list.push_back(
        {{"index", r.index},
         {"id", r.id},
         {"label", r.label},
         {"technique", r.technique},
         {"graph", r.graph},
         {"scene", r.scene},
         {"camera", r.camera},
         {"width", r.width},
         {"height", r.height},
         {"overrides", r.overrides},
         {"swept", r.swept},
         {"warmup_frames", r.warmup_frames},
         {"frames", r.frames},
         {"gpu_ms", spread_json(r.times.gpu_total_ms)},
         {"cpu_ms", spread_json(r.times.cpu_total_ms)},
         {"passes", passes},
         {"metrics", {{"full", metrics_json(r.full)}, {"indirect", metrics_json(r.indirect)}}},
         {"reference_key", r.reference_key},
         {"reference_cache_hit", r.reference_cache_hit},
         {"same_bounce", same_bounce_json(r.same_bounce)},
         {"images",
          {{"image", r.image_png}, {"reference", r.reference_png}, {"heat_map", r.heat_map_png}}},
         {"wall_seconds", r.wall_seconds},
         {"gpu_memory_bytes", r.gpu_memory_bytes},
         {"gpu_memory_unshared_bytes", r.gpu_memory_unshared_bytes}});
  }
  doc["results"] = list;
  return doc;
}

BenchResults results_from_json(const json& doc, const std::string& file) {
  const Reader read(file);
  if (!doc.is_object() || !doc.contains("format") || doc["format"] != "voxgi-bench-results-1") {
    read.fail("format", "not a voxgi bench results file (expected \"voxgi-bench-results-1\")");
  }
  BenchResults results;
  results.name = read.text(doc, "name", "");
  results.bench_file = read.text(doc, "bench_file", "");
  results.bench_hash = read.text(doc, "bench_hash", "");
  results.device = read.text(doc, "device", "");
  const json& reference = read.at(doc, "reference", "");
  results.reference_graph = read.text(reference, "graph", "reference.");
  results.reference_frames = static_cast<uint32_t>(read.count(reference, "frames", "reference."));
  // Results written before the field existed measured static frames.
  results.changes = doc.contains("changes") ? read.text(doc, "changes", "") : "none";
  results.configurations_total = read.count(doc, "configurations_total", "");
  const json& shards = read.at(doc, "shards", "");
  if (!shards.is_array()) read.fail("shards", "expected an array");
  for (const json& shard : shards) {
    if (!shard.is_string()) read.fail("shards", "expected strings like \"1/2\"");
    results.shards.push_back(shard.get<std::string>());
  }
  const json& list = read.at(doc, "results", "");
  if (!list.is_array()) read.fail("results", "expected an array");
  for (size_t i = 0; i < list.size(); ++i) {
    const json& item = list[i];
    const std::string where = "results[" + std::to_string(i) + "].";
    ConfigResult r;
    r.index = read.count(item, "index", where);
    r.id = read.text(item, "id", where);
    r.label = read.text(item, "label", where);
    r.technique = read.text(item, "technique", where);
    r.graph = read.text(item, "graph", where);
    r.scene = read.text(item, "scene", where);
    r.camera = read.text(item, "camera", where);
    r.width = static_cast<uint32_t>(read.count(item, "width", where));
    r.height = static_cast<uint32_t>(read.count(item, "height", where));
    r.overrides = read.strings(item, "overrides", where);
    r.swept = read.strings(item, "swept", where);
    r.warmup_frames = static_cast<uint32_t>(read.count(item, "warmup_frames", where));
    r.frames = static_cast<uint32_t>(read.count(item, "frames", where));
    r.times.gpu_total_ms = read.spread(item, "gpu_ms", where);
    r.gpu_memory_bytes = item.value("gpu_memory_bytes", uint64_t{0});
    r.gpu_memory_unshared_bytes = item.value("gpu_memory_unshared_bytes", uint64_t{0});
    r.times.cpu_total_ms = read.spread(item, "cpu_ms", where);
    const json& passes = read.at(item, "passes", where);
    if (!passes.is_array()) read.fail(where + "passes", "expected an array");
    for (size_t k = 0; k < passes.size(); ++k) {
      const std::string pw = where + "passes[" + std::to_string(k) + "].";
      PassTime p;
      p.pass = read.text(passes[k], "pass", pw);
      p.type = read.text(passes[k], "type", pw);
      p.gpu_ms = read.spread(passes[k], "gpu_ms", pw);
      p.share_ms = read.number(passes[k], "share_ms", pw);
      p.frames = static_cast<uint32_t>(read.count(passes[k], "frames", pw));
      p.skipped = static_cast<uint32_t>(read.count(passes[k], "skipped_frames", pw));
      p.skip_reason = read.text(passes[k], "skip_reason", pw);
      r.times.passes.push_back(std::move(p));
    }
    const json& metrics = read.at(item, "metrics", where);
    r.full = read.metrics(metrics, "full", where + "metrics.");
    r.indirect = read.metrics(metrics, "indirect", where + "metrics.");
    r.reference_key = read.text(item, "reference_key", where);
    r.reference_cache_hit = read.flag(item, "reference_cache_hit", where);
    r.same_bounce = read.same_bounce(item, "same_bounce", where);
    const json& images = read.at(item, "images", where);
    r.image_png = read.text(images, "image", where + "images.");
    r.reference_png = read.text(images, "reference", where + "images.");
    r.heat_map_png = read.text(images, "heat_map", where + "images.");
    r.wall_seconds = read.number(item, "wall_seconds", where);
    results.results.push_back(std::move(r));
  }
  return results;
}

BenchResults read_results(const std::filesystem::path& results_json) {
  std::ifstream in(results_json, std::ios::binary);
  if (!in)
    throw std::runtime_error(results_json.string() + ": cannot read (missing or unreadable)");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  json doc;
  try {
    doc = json::parse(text);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(results_json.string() + ": not valid JSON: " + e.what());
  }
  return results_from_json(doc, results_json.string());
}

std::string results_csv(const BenchResults& results) {
  std::ostringstream out;
  out << "index,id,technique,label,graph,scene,camera,width,height,overrides,warmup_frames,"
         "frames,gpu_ms_median,gpu_ms_p10,gpu_ms_p90,gpu_ms_min,gpu_ms_max,cpu_ms_median,"
         "rel_mse,rmse,ssim_luminance,luminance_bias,non_finite_pixels,indirect_rel_mse,"
         "indirect_rmse,indirect_ssim_luminance,indirect_luminance_bias,reference_key,"
         "reference_cache_hit,hdr_flip,indirect_hdr_flip,indirect_bounces,indirect_brdf,"
         "same_bounce_rel_mse,same_bounce_ssim_luminance,same_bounce_hdr_flip,"
         "same_bounce_luminance_bias,full_indirect_rel_mse,full_indirect_ssim_luminance,"
         "full_indirect_hdr_flip,full_indirect_luminance_bias,missing_indirect_fraction,"
         "same_bounce_reference_key,gpu_memory_bytes,same_bounce_reference_noise_rel_mse,"
         "indirect_faces\n";
  for (const ConfigResult& r : results.results) {
    std::string overrides;
    for (const auto& [k, v] : r.overrides)
      overrides += (overrides.empty() ? "" : " ") + k + "=" + v;
    const Spread& t = r.times.gpu_total_ms;
    out << r.index << ',' << r.id << ',' << csv_field(r.technique) << ',' << csv_field(r.label)
        << ',' << csv_field(r.graph) << ',' << csv_field(r.scene) << ',' << csv_field(r.camera)
        << ',' << r.width << ',' << r.height << ',' << csv_field(overrides) << ','
        << r.warmup_frames << ',' << r.frames << ',' << number_text(t.median) << ','
        << number_text(t.p10) << ',' << number_text(t.p90) << ',' << number_text(t.min) << ','
        << number_text(t.max) << ',' << number_text(r.times.cpu_total_ms.median);
    for (const auto* m : {&r.full, &r.indirect}) {
      if (*m) {
        out << ',' << number_text((*m)->rel_mse) << ',' << number_text((*m)->rmse) << ','
            << number_text((*m)->ssim_luminance) << ',' << number_text((*m)->luminance_bias);
        if (m == &r.full) out << ',' << (*m)->non_finite_pixels;
      } else {
        out << (m == &r.full ? ",,,,," : ",,,,");
      }
    }
    out << ',' << r.reference_key << ',' << (r.reference_cache_hit ? "true" : "false");
    for (const auto* m : {&r.full, &r.indirect}) {
      out << ',' << (*m ? number_text((*m)->hdr_flip) : "");
    }
    if (const std::optional<SameBounceResult>& s = r.same_bounce) {
      out << ',' << s->bounces << ',' << s->brdf;
      for (const auto* m : {&s->indirect, &s->full_indirect}) {
        if (*m) {
          out << ',' << number_text((*m)->rel_mse) << ',' << number_text((*m)->ssim_luminance)
              << ',' << number_text((*m)->hdr_flip) << ',' << number_text((*m)->luminance_bias);
        } else {
          out << ",,,,";
        }
      }
      out << ',' << (s->missing_fraction ? number_text(*s->missing_fraction) : "") << ','
          << s->reference_key;
    } else {
      out << ",,,,,,,,,,,,";
    }
    out << ',' << r.gpu_memory_bytes << ',';
    if (r.same_bounce && r.same_bounce->reference_noise_rel_mse) {
      out << number_text(*r.same_bounce->reference_noise_rel_mse);
    }
    out << ',' << (r.same_bounce ? r.same_bounce->faces : "");
    out << '\n';
  }
  return out.str();
}

void write_results(const std::filesystem::path& dir, const BenchResults& results) {
  write_file_atomically(dir / "results.json", to_json(results).dump(2) + "\n");
  write_file_atomically(dir / "results.csv", results_csv(results));
}

}  // namespace voxgi::cli
