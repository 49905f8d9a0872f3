#pragma once
// A private virtual X display (Xvfb) for window tests, started on a free display number and
// stopped when the object goes away.

#include <sys/types.h>

#include <string>

namespace voxgi::test {

class XvfbDisplay {
 public:
  // Starts Xvfb and waits (up to 10 s) for its socket. available() is false when Xvfb is not
  // installed; error() says why it could not start otherwise.
  XvfbDisplay();
  ~XvfbDisplay();
  XvfbDisplay(const XvfbDisplay&) = delete;
  XvfbDisplay& operator=(const XvfbDisplay&) = delete;

  bool installed() const { return installed_; }
  bool running() const { return pid_ > 0; }
  const std::string& error() const { return error_; }
  std::string display() const;  // for DISPLAY, e.g. ":101"

 private:
  bool installed_ = false;
  pid_t pid_ = -1;
  int number_ = -1;
  std::string error_;
};

// True when the tests run under CI (env CI=true): a missing Xvfb is a failure there, not a skip.
bool running_in_ci();

}  // namespace voxgi::test
