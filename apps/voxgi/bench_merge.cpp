// voxgi bench merge OUT_DIR SHARD_DIR...: joins the results of `voxgi bench --shard i/n` runs
// into one results.json, results.csv and report, refusing shards of different benches.

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <map>

#include "apps/voxgi/bench_results.hpp"
#include "apps/voxgi/bench_subcommands.hpp"
#include "apps/voxgi/cli_args.hpp"
#include "apps/voxgi/report_markdown.hpp"

namespace voxgi::cli {
namespace {

namespace fs = std::filesystem;

// Copies a file of a shard folder into the merged folder (same relative path).
void copy_into(const fs::path& from_dir, const fs::path& to_dir, const std::string& relative) {
  if (relative.empty()) return;
  const fs::path from = from_dir / relative, to = to_dir / relative;
  std::error_code ec;
  if (fs::equivalent(from, to, ec)) return;  // merging into one of the shard folders
  fs::create_directories(to.parent_path(), ec);
  fs::copy_file(from, to, fs::copy_options::overwrite_existing, ec);
  if (ec) {
    throw std::runtime_error("voxgi bench merge: cannot copy '" + from.string() + "' to '" +
                             to.string() + "': " + ec.message());
  }
}

}  // namespace

int bench_merge_command(const std::vector<std::string>& argv) {
  if (argv.size() == 1 && (argv[0] == "--help" || argv[0] == "-h")) {
    std::cout << kBenchUsage;
    return 0;
  }
  if (argv.size() < 2) {
    throw UsageError("voxgi bench merge: expected OUT_DIR and at least one SHARD_DIR");
  }
  for (const std::string& arg : argv) {
    if (arg.rfind("--", 0) == 0)
      throw UsageError("voxgi bench merge: unknown option '" + arg + "'");
  }
  const fs::path out_dir = argv[0];
  BenchResults merged;
  std::map<size_t, std::string> owner;  // configuration index → shard folder
  for (size_t i = 1; i < argv.size(); ++i) {
    const fs::path shard_dir = argv[i];
    const BenchResults shard = read_results(shard_dir / "results.json");
    if (i == 1) {
      merged = shard;
      merged.results.clear();
      merged.shards.clear();
    } else if (shard.bench_hash != merged.bench_hash ||
               shard.configurations_total != merged.configurations_total) {
      throw std::runtime_error("voxgi bench merge: '" + shard_dir.string() +
                               "' comes from a different bench file (or version of it) than '" +
                               argv[1] + "' (" + shard.bench_file + ")");
    }
    merged.shards.insert(merged.shards.end(), shard.shards.begin(), shard.shards.end());
    if (shard.device != merged.device && merged.device.find(shard.device) == std::string::npos) {
      merged.device += "; " + shard.device;
    }
    for (const ConfigResult& r : shard.results) {
      if (auto [it, inserted] = owner.emplace(r.index, shard_dir.string()); !inserted) {
        throw std::runtime_error("voxgi bench merge: configuration " + r.id + " is in both '" +
                                 it->second + "' and '" + shard_dir.string() + "'");
      }
      for (const std::string* file : {&r.image_png, &r.reference_png, &r.heat_map_png}) {
        copy_into(shard_dir, out_dir, *file);
      }
      merged.results.push_back(r);
    }
  }
  std::sort(merged.results.begin(), merged.results.end(),
            [](const ConfigResult& a, const ConfigResult& b) { return a.index < b.index; });
  write_results(out_dir, merged);
  write_report(out_dir, merged);
  std::cerr << "voxgi: bench merge: " << merged.results.size() << " of "
            << merged.configurations_total << " configurations from " << argv.size() - 1
            << " shard folder(s)\n";
  if (const std::vector<size_t> missing = merged.missing(); !missing.empty()) {
    std::cerr << "voxgi: warning: no result for configuration(s)";
    for (size_t m : missing) std::cerr << " " << m;
    std::cerr << " (a shard is missing?)\n";
  }
  std::cerr << "voxgi: wrote " << (out_dir / "results.json").string() << ", "
            << (out_dir / "results.csv").string() << ", " << (out_dir / "report.md").string()
            << "\n";
  return 0;
}

}  // namespace voxgi::cli
