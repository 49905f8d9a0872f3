#pragma once
// Progress of a bench on stderr: a redrawn bar with the time left when stderr is a terminal,
// one plain line per configuration otherwise (logs, CI, tests).

#include <chrono>
#include <cstddef>
#include <ostream>
#include <string>

namespace voxgi::cli {

class BenchProgress {
 public:
  BenchProgress(std::ostream& out, size_t total, bool terminal);

  // A message that must not be overwritten by the bar (cache hits, warnings).
  void note(const std::string& line);
  void starting(const std::string& what);
  // Within a long step (the reference): the bar on a terminal, else a line every 30 s.
  void step(const std::string& what);
  void finished(const std::string& summary);
  void done();

  // "1h02m", "3m07s", "12s".
  static std::string duration_text(double seconds);

 private:
  void draw(const std::string& what);

  std::ostream& out_;
  size_t total_;
  size_t finished_ = 0;
  bool terminal_;
  bool bar_shown_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_line_;
};

}  // namespace voxgi::cli
