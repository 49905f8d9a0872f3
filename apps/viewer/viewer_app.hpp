#pragma once
// The interactive viewer: a scene, several graphs (one active, another to compare with), a
// camera, light edits, animation time, inspection of any image resource, hot reload of graph
// files and shaders, and a script that can drive all of it.

#include <chrono>
#include <deque>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "apps/viewer/camera_controller.hpp"
#include "apps/viewer/image_compose.hpp"
#include "apps/viewer/script.hpp"
#include "apps/viewer/viewer_options.hpp"
#include "engine/image/image.hpp"
#include "engine/runtime/file_watcher.hpp"
#include "engine/runtime/graph_instance.hpp"
#include "engine/runtime/runtime.hpp"
#include "engine/runtime/timings.hpp"

struct GLFWwindow;

namespace voxgi::viewer {

class Presenter;

class ViewerApp {
 public:
  // Loads the scene and the graph files and opens the window. Throws with a message naming
  // the file or the reason (no display, no Vulkan device, bad scene or graph).
  explicit ViewerApp(const ViewerOptions& options);
  ~ViewerApp();
  ViewerApp(const ViewerApp&) = delete;
  ViewerApp& operator=(const ViewerApp&) = delete;

  // The main loop until the window closes, Escape, or the script's `quit`. Returns the exit
  // code: non-zero after a script error or validation messages.
  int run();

  void on_key(int key);
  void on_mouse_move(double x, double y);
  void on_scroll(double dy);

 private:
  struct GraphSlot {
    std::filesystem::path file;
    std::unique_ptr<runtime::GraphInstance> instance;  // the last good build
    std::map<std::string, std::string> edits;          // parameters changed in the viewer
    std::string error;                                 // of the last failed build, shown
    runtime::TimingsHistory timings{120};
    uint64_t build_id = 0;  // which build `instance` is (a shared pair follows it)
  };

  // Split and difference views run the two graphs as one (graph::merge_for_ab), so that the
  // passes they share run once per frame; the panel names them.
  struct SharedPair {
    uint64_t a_build = 0, b_build = 0, edits = 0;  // what it was merged from
    std::unique_ptr<runtime::GraphInstance> instance;
    std::vector<std::string> shared;  // passes run once for both
    std::string error;                // why the two run apart, when they could not merge
    runtime::TimingsHistory timings{120};
  };

  // Builds (or rebuilds) a slot; on failure keeps the previous instance and records the error.
  bool build(size_t slot, bool reread_file);
  void switch_graph(size_t slot);
  // A named variant of the slot's graph file ("" for the file as written); throws when it
  // does not build, leaving the last good build running.
  void set_variant(size_t slot, const std::string& variant);
  void next_variant(size_t slot);             // V: the file, its variants in order, the file again
  std::string slot_label(size_t slot) const;  // "vct.json #half"
  void set_inspect(const std::string& resource);
  void set_param(size_t slot, const std::string& key, const std::string& value);
  void check_files();
  void report(const std::string& message, bool is_error);

  void update_scene(runtime::FrameChanges& changes);
  void apply_light_edits();
  void render_frame();
  void compose();
  void draw_panel();
  void draw_params_panel(size_t slot);
  void draw_timings_table(const runtime::TimingsHistory& history, const std::string& id);
  // The merged graph of the active and the compared slot, built when they change; nullptr when
  // they could not be merged (then each renders on its own).
  runtime::GraphInstance* shared_pair();
  // Applies a slot's parameter edit to the pair as well; false when it must be merged again
  // (the edited pass was shared, or the pair refuses the edit).
  bool edit_pair(size_t slot, const std::string& key, const std::string& value);
  void draw_inspect_panel();
  void draw_lights_panel();
  void handle_held_keys(double dt);

  void screenshot(const std::filesystem::path& stem);
  void window_shot(const std::filesystem::path& file);
  // Runs script commands until one needs frames; false once `quit` ran.
  bool step_script();
  void run_command(const ScriptCommand& command);

  ViewerOptions options_;
  scene::Camera start_camera_;
  std::unique_ptr<runtime::Runtime> runtime_;
  GLFWwindow* window_ = nullptr;
  std::unique_ptr<Presenter> presenter_;
  bool imgui_ready_ = false;

  std::vector<GraphSlot> slots_;
  uint64_t builds_ = 0;       // numbers each successful build
  uint64_t param_edits_ = 0;  // counts live parameter edits
  SharedPair pair_;
  bool pair_shown_ = false;  // the last frame came from pair_
  size_t active_ = 0;
  size_t compare_ = 0;
  bool split_ = false;
  bool difference_ = false;
  float wipe_ = 0.5f;
  float difference_gain_ = 4.0f;

  std::string inspect_;  // resource shown instead of the output; "" for none
  int inspect_level_ = 0;
  int inspect_slice_ = 0;
  float exposure_ = 0.0f;
  Channels channels_ = Channels::RGB;

  CameraController camera_;
  int scene_camera_ = -1;  // -1: the start camera
  struct LightEdit {
    bool edited = false;
    glm::vec3 position{0.0f};
    glm::vec3 direction{0.0f, 0.0f, -1.0f};
    float intensity = 1.0f;
    glm::vec3 color{1.0f};
  };
  std::vector<LightEdit> light_edits_;
  bool lights_dirty_ = true;
  bool playing_ = false;
  double time_ = 0.0;
  int pending_steps_ = 0;

  // The last frame, as shown (display) and as linear radiance, without the UI.
  image::ImageRGBA32F shown_display_;
  image::ImageRGBA32F shown_linear_;
  std::string shown_caption_;
  std::vector<float> frame_ms_;
  std::chrono::steady_clock::time_point last_frame_;
  uint64_t frames_ = 0;

  runtime::FileWatcher watcher_;
  std::chrono::steady_clock::time_point last_poll_;

  std::string message_;
  bool message_is_error_ = false;
  bool show_panel_ = true;
  bool quiet_ = false;                   // report() keeps messages off stderr
  std::set<std::string> open_sections_;  // panel sections to unfold on the next frame
  bool header(const char* label, const char* section, bool open_by_default);
  int screenshot_counter_ = 0;

  std::vector<ScriptCommand> script_;
  size_t script_pos_ = 0;
  int script_frames_ = 0;  // frames to render before the next command
  std::optional<std::filesystem::path> pending_screenshot_;
  std::optional<std::filesystem::path> pending_window_shot_;
  std::optional<std::filesystem::path> waiting_for_;
  std::chrono::steady_clock::time_point wait_deadline_;
  bool quit_ = false;
  int exit_code_ = 0;
  double mouse_x_ = 0.0, mouse_y_ = 0.0;
  bool mouse_known_ = false;
};

}  // namespace voxgi::viewer
