#include "apps/voxgi/bench_progress.hpp"

#include <cstdio>

namespace voxgi::cli {

BenchProgress::BenchProgress(std::ostream& out, size_t total, bool terminal)
    : out_(out),
      total_(total),
      terminal_(terminal),
      start_(std::chrono::steady_clock::now()),
      last_line_(start_) {}

std::string BenchProgress::duration_text(double seconds) {
  const long s = static_cast<long>(seconds + 0.5);
  char text[32];
  if (s >= 3600) {
    std::snprintf(text, sizeof text, "%ldh%02ldm", s / 3600, (s / 60) % 60);
  } else if (s >= 60) {
    std::snprintf(text, sizeof text, "%ldm%02lds", s / 60, s % 60);
  } else {
    std::snprintf(text, sizeof text, "%lds", s);
  }
  return text;
}

void BenchProgress::note(const std::string& line) {
  if (terminal_ && bar_shown_) out_ << "\r\033[K";
  out_ << line << "\n";
  bar_shown_ = false;
  out_.flush();
}

void BenchProgress::draw(const std::string& what) {
  constexpr size_t kWidth = 30;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const size_t filled = total_ ? finished_ * kWidth / total_ : kWidth;
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  // The mean time per finished configuration times what is left.
  std::string left = "left ?";
  if (finished_ > 0) {
    left = "left ~" + duration_text(elapsed / static_cast<double>(finished_) *
                                    static_cast<double>(total_ - finished_));
  }
  std::string line = "[" + bar + "] " + std::to_string(finished_) + "/" + std::to_string(total_) +
                     "  " + duration_text(elapsed) + " elapsed, " + left + "  " + what;
  if (line.size() > 120) line.resize(120);
  out_ << "\r\033[K" << line;
  out_.flush();
  bar_shown_ = true;
}

void BenchProgress::starting(const std::string& what) {
  if (terminal_) draw(what);
}

void BenchProgress::step(const std::string& what) {
  if (terminal_) {
    draw(what);
    return;
  }
  const auto now = std::chrono::steady_clock::now();
  if (now - last_line_ < std::chrono::seconds(30)) return;
  last_line_ = now;
  out_ << "voxgi: bench: " << what << "\n";
  out_.flush();
}

void BenchProgress::finished(const std::string& summary) {
  ++finished_;
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double left =
      elapsed / static_cast<double>(finished_) * static_cast<double>(total_ - finished_);
  if (terminal_) {
    note(summary);
    draw("");
  } else {
    out_ << "voxgi: bench: [" << finished_ << "/" << total_ << "] " << summary << " (left ~"
         << duration_text(left) << ")\n";
    out_.flush();
  }
}

void BenchProgress::done() {
  if (terminal_ && bar_shown_) {
    out_ << "\r\033[K";
    out_.flush();
    bar_shown_ = false;
  }
}

}  // namespace voxgi::cli
