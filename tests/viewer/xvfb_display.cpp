#include "tests/viewer/xvfb_display.hpp"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

namespace voxgi::test {
namespace {

std::string find_xvfb() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "/usr/bin:/bin");
  for (std::string dir; std::getline(dirs, dir, ':');) {
    const std::filesystem::path candidate = std::filesystem::path(dir) / "Xvfb";
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

// Built with append(): GCC 12 warns falsely (-Wrestrict) on "literal" + std::string here.
std::string joined(const char* prefix, int number, const char* suffix = "") {
  std::string text(prefix);
  text.append(std::to_string(number)).append(suffix);
  return text;
}

std::string socket_path(int number) {
  return joined("/tmp/.X11-unix/X", number);
}

bool socket_exists(int number) {
  return std::filesystem::exists(socket_path(number)) ||
         std::filesystem::exists(joined("/tmp/.X", number, "-lock"));
}

}  // namespace

bool running_in_ci() {
  const char* ci = std::getenv("CI");
  return ci && std::string(ci) == "true";
}

XvfbDisplay::XvfbDisplay() {
  const std::string xvfb = find_xvfb();
  if (xvfb.empty()) return;
  installed_ = true;
  // Several test processes may run at once: spread display numbers by process id.
  for (int attempt = 0; attempt < 20 && pid_ < 0; ++attempt) {
    const int number = 100 + static_cast<int>((::getpid() * 7 + attempt * 13) % 400);
    if (socket_exists(number)) continue;
    const std::string display = joined(":", number);
    const pid_t pid = ::fork();
    if (pid < 0) {
      error_ = "fork failed";
      return;
    }
    if (pid == 0) {
      const int null_fd = ::open("/dev/null", O_RDWR);
      if (null_fd >= 0) {
        ::dup2(null_fd, STDIN_FILENO);
        ::dup2(null_fd, STDOUT_FILENO);
        ::dup2(null_fd, STDERR_FILENO);
      }
      ::execl(xvfb.c_str(), "Xvfb", display.c_str(), "-screen", "0", "1024x768x24", "-nolisten",
              "tcp", static_cast<char*>(nullptr));
      ::_exit(127);
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    bool up = false, exited = false;
    while (std::chrono::steady_clock::now() < deadline) {
      if (std::filesystem::exists(socket_path(number))) {
        up = true;
        break;
      }
      int status = 0;
      if (::waitpid(pid, &status, WNOHANG) == pid) {
        exited = true;  // e.g. the number was taken meanwhile: try another
        break;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    if (up) {
      pid_ = pid;
      number_ = number;
    } else if (!exited) {
      ::kill(pid, SIGTERM);
      ::waitpid(pid, nullptr, 0);
      error_ = "Xvfb " + display + " did not open its socket within 10 s";
    }
  }
  if (pid_ < 0 && error_.empty()) error_ = "Xvfb found no free display number";
}

std::string XvfbDisplay::display() const {
  return joined(":", number_);
}

XvfbDisplay::~XvfbDisplay() {
  if (pid_ > 0) {
    ::kill(pid_, SIGTERM);
    ::waitpid(pid_, nullptr, 0);
  }
}

}  // namespace voxgi::test
