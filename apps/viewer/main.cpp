// voxgi-viewer: renders a scene through one or more graph files in a window, with a panel to
// switch and compare graphs, edit parameters and lights, watch timings and inspect resources.
// Exit codes: 0 done, 1 an error (message on stderr), 2 a wrong command line.

#include <exception>
#include <iostream>
#include <string>
#include <vector>

#include "apps/viewer/viewer_app.hpp"
#include "apps/viewer/viewer_options.hpp"

int main(int argc, char** argv) {
  using namespace voxgi::viewer;
  ViewerOptions options;
  try {
    options = parse_viewer_options(std::vector<std::string>(argv + 1, argv + argc));
  } catch (const UsageError& e) {
    std::cerr << "voxgi-viewer: error: " << e.what() << "\n" << viewer_usage();
    return 2;
  }
  if (options.help) {
    std::cout << viewer_usage();
    return 0;
  }
  try {
    ViewerApp app(options);
    return app.run();
  } catch (const std::exception& e) {
    std::cerr << "voxgi-viewer: error: " << e.what() << "\n";
    return 1;
  }
}
