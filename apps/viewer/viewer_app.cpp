#include "apps/viewer/viewer_app.hpp"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <thread>

#include "apps/viewer/presenter.hpp"
#include "engine/graph/ab_merge.hpp"
#include "engine/graph/diagnostics.hpp"
#include "engine/image/image.hpp"
#include "engine/runtime/output_files.hpp"
#include "engine/runtime/scene_source.hpp"

namespace voxgi::viewer {

namespace fs = std::filesystem;

namespace {

constexpr int kPanelWidth = 440;
constexpr double kScriptFrameSeconds = 1.0 / 30.0;  // scripted sessions advance time per frame
constexpr const char* kInspectOutput = "viewer.inspect";

ViewerApp* app_of(GLFWwindow* window) {
  return static_cast<ViewerApp*>(glfwGetWindowUserPointer(window));
}

void key_callback(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard) return;
  if (ViewerApp* app = app_of(window)) app->on_key(key);
}

void cursor_callback(GLFWwindow* window, double x, double y) {
  if (ViewerApp* app = app_of(window)) app->on_mouse_move(x, y);
}

void scroll_callback(GLFWwindow* window, double, double dy) {
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
  if (ViewerApp* app = app_of(window)) app->on_scroll(dy);
}

float scene_extent(const scene::Scene& scene) {
  glm::vec3 mn, mx;
  scene.bounds(mn, mx);
  const glm::vec3 size = mx - mn;
  return std::max({size.x, size.y, size.z, 1e-3f});
}

}  // namespace

ViewerApp::ViewerApp(const ViewerOptions& options) : options_(options) {
  if (options_.script) script_ = load_script(*options_.script);
  // Scene and graph files first: their errors need no window.
  scene::Scene scene = runtime::load_scene(options_.scene);
  for (const std::string& warning : scene.warnings)
    std::cerr << "voxgi-viewer: warning: " << scene.source << ": " << warning << "\n";
  start_camera_ = runtime::choose_camera(scene, options_.camera);
  const std::map<std::string, std::string> overrides = runtime::parse_overrides(options_.sets);
  for (const std::string& graph : options_.graphs) {
    // "FILE#VARIANT" shows one of the file's named variants: two slots of one file with
    // different variants make an A/B of the variants.
    const size_t hash = graph.rfind('#');
    GraphSlot slot;
    slot.file = runtime::resolve_graph_path(graph.substr(0, hash));
    const graph::GraphDesc desc = graph::load_graph_file(slot.file);  // throws naming the file
    slot.edits = overrides;
    if (hash != std::string::npos) {
      const std::string variant = graph.substr(hash + 1);
      if (!desc.find_variant(variant)) {
        std::string names;
        for (const graph::VariantDesc& v : desc.variants)
          names += (names.empty() ? "" : ", ") + v.name;
        throw std::invalid_argument(
            "--graph " + graph + ": " + slot.file.string() + " has no variant '" + variant + "' (" +
            (names.empty() ? "it has none" : "its variants: " + names) + ")");
      }
      slot.edits[graph::kVariantKey] = variant;
    }
    slots_.push_back(std::move(slot));
  }
  compare_ = slots_.size() > 1 ? 1 : 0;

  glfwSetErrorCallback([](int code, const char* description) {
    std::cerr << "voxgi-viewer: GLFW error " << code << ": " << description << "\n";
  });
  if (!glfwInit()) {
    throw std::runtime_error(
        "cannot open a window: no display (set DISPLAY, or run under xvfb-run for a virtual "
        "one)");
  }
  if (!glfwVulkanSupported()) {
    glfwTerminate();
    throw std::runtime_error(
        "cannot open a window: GLFW finds no Vulkan loader with surface support");
  }
  uint32_t count = 0;
  const char** required = glfwGetRequiredInstanceExtensions(&count);
  runtime::RuntimeOptions runtime_options;
  runtime_options.device = options_.device;
  runtime_options.validation = options_.validation;
  runtime_options.instance_extensions.assign(required, required + count);
  runtime_options.device_extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  runtime_ = std::make_unique<runtime::Runtime>(runtime_options, std::move(scene));
  std::cerr << "voxgi-viewer: device: " << runtime_->context().device_summary() << "\n";
  light_edits_.resize(runtime_->scene().lights.size());
  camera_.reset(start_camera_, scene_extent(runtime_->scene()));
  playing_ = !runtime_->scene().animations.empty() && script_.empty();

  // The first graph must build; the others build when first shown.
  quiet_ = true;  // main() prints the error of the first build
  const bool built = build(0, false);
  quiet_ = false;
  if (!built) throw std::runtime_error(slots_[0].file.string() + ": " + slots_[0].error);

  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  const int window_w = static_cast<int>(options_.width) + kPanelWidth;
  const int window_h = std::max(static_cast<int>(options_.height), 640);
  window_ = glfwCreateWindow(window_w, window_h, "voxgi-viewer", nullptr, nullptr);
  if (!window_) throw std::runtime_error("cannot open a window (see the GLFW error above)");
  glfwSetWindowUserPointer(window_, this);
  // Installed before ImGui's backend, which chains to them.
  glfwSetKeyCallback(window_, key_callback);
  glfwSetCursorPosCallback(window_, cursor_callback);
  glfwSetScrollCallback(window_, scroll_callback);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini left in the working directory
  ImGui::StyleColorsDark();
  ImGui_ImplGlfw_InitForVulkan(window_, true);
  imgui_ready_ = true;
  presenter_ = std::make_unique<Presenter>(runtime_->context(), window_);

  for (const GraphSlot& slot : slots_) watcher_.watch_file(slot.file);
  watcher_.watch_tree(gpu::ShaderCompiler::default_shader_root());
  last_poll_ = last_frame_ = std::chrono::steady_clock::now();
}

ViewerApp::~ViewerApp() {
  if (runtime_) runtime_->context().wait_idle();
  presenter_.reset();
  if (imgui_ready_) {
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  slots_.clear();
  if (window_) glfwDestroyWindow(window_);
  runtime_.reset();
  glfwTerminate();
}

void ViewerApp::report(const std::string& message, bool is_error) {
  // A problem that repeats every frame is said once.
  if (is_error && message_is_error_ && message == message_) return;
  message_ = message;
  message_is_error_ = is_error;
  if (quiet_) return;
  std::cerr << "voxgi-viewer: " << (is_error ? "error: " : "") << message << "\n";
}

bool ViewerApp::build(size_t index, bool reread_file) {
  GraphSlot& slot = slots_[index];
  try {
    graph::GraphDesc desc =
        reread_file || !slot.instance ? graph::load_graph_file(slot.file) : slot.instance->desc();
    runtime::GraphSettings settings;
    settings.width = options_.width;
    settings.height = options_.height;
    settings.overrides = slot.edits;
    if (!inspect_.empty() && index == active_) {
      settings.extra_outputs[kInspectOutput] = inspect_;
      settings.alias_transients = false;  // what is inspected must not share memory
    }
    // Editing a fragment the graph includes reloads it too.
    for (const std::string& fragment : desc.included_files) watcher_.watch_file(fragment);
    auto fresh = std::make_unique<runtime::GraphInstance>(*runtime_, std::move(desc), settings);
    slot.instance = std::move(fresh);
    slot.error.clear();
    slot.timings.clear();
    slot.build_id = ++builds_;
    return true;
  } catch (const std::exception& e) {
    slot.error = e.what();
    report(slot.file.string() + ": " + e.what() +
               (slot.instance ? "\n(the last good version keeps running)" : ""),
           true);
    return false;
  }
}

std::string ViewerApp::slot_label(size_t index) const {
  const GraphSlot& slot = slots_[index];
  auto it = slot.edits.find(graph::kVariantKey);
  std::string label = slot.file.filename().string();
  if (it != slot.edits.end() && !it->second.empty()) label += " #" + it->second;
  return label;
}

void ViewerApp::set_variant(size_t index, const std::string& variant) {
  GraphSlot& slot = slots_[index];
  const auto previous = slot.edits.find(graph::kVariantKey);
  const std::string before = previous == slot.edits.end() ? std::string() : previous->second;
  slot.edits[graph::kVariantKey] = variant;
  if (!build(index, false)) {
    slot.edits[graph::kVariantKey] = before;  // the last good build keeps running
    throw std::runtime_error("variant '" + variant + "' failed to build: " + slot.error);
  }
  report("graph " + std::to_string(index + 1) + ": " + slot_label(index), false);
}

void ViewerApp::next_variant(size_t index) {
  if (!slots_[index].instance) return;
  const std::vector<std::string>& variants = slots_[index].instance->compiled().variants;
  if (variants.empty()) {
    report(slots_[index].file.string() + " names no variants", true);
    return;
  }
  // The file as written, then each variant in file order, then the file again.
  const std::string& current = slots_[index].instance->compiled().variant;
  auto it = std::find(variants.begin(), variants.end(), current);
  const std::string next = current.empty()            ? variants.front()
                           : it + 1 == variants.end() ? std::string()
                                                      : *(it + 1);
  try {
    set_variant(index, next);
  } catch (const std::exception& e) {
    report(e.what(), true);
  }
}

void ViewerApp::switch_graph(size_t index) {
  if (index >= slots_.size()) {
    report("graph " + std::to_string(index + 1) + ": only " + std::to_string(slots_.size()) +
               " graph(s) loaded",
           true);
    return;
  }
  const size_t previous = active_;
  active_ = index;
  // The inspected resource is an extra output of the active graph only.
  if (!inspect_.empty() && previous != index && slots_[previous].instance) build(previous, false);
  if (!slots_[index].instance || !inspect_.empty()) {
    bool built = build(index, false);
    if (!built && !inspect_.empty()) {
      // The inspected resource may not exist in this graph: show its output instead.
      inspect_.clear();
      built = build(index, false);
    }
    if (!built && !slots_[index].instance) {
      active_ = previous;
      return;
    }
  }
  if (compare_ == active_ && slots_.size() > 1) compare_ = (active_ + 1) % slots_.size();
  report("graph " + std::to_string(index + 1) + ": " + slot_label(index), false);
}

void ViewerApp::set_inspect(const std::string& resource) {
  const std::string previous = inspect_;
  inspect_ = resource;
  inspect_level_ = inspect_slice_ = 0;
  if (!build(active_, false)) inspect_ = previous;
}

void ViewerApp::set_param(size_t index, const std::string& key, const std::string& value) {
  GraphSlot& slot = slots_[index];
  if (!slot.instance) return;
  try {
    slot.instance->set_param(key, value);
    slot.edits[key] = value;
    if (!edit_pair(index, key, value)) ++param_edits_;  // the pair is merged again
  } catch (const std::exception& e) {
    report(e.what(), true);
    throw;
  }
}

void ViewerApp::check_files() {
  last_poll_ = std::chrono::steady_clock::now();
  const std::vector<fs::path> changed = watcher_.poll();
  if (changed.empty()) return;
  const fs::path shader_root = gpu::ShaderCompiler::default_shader_root();
  bool shaders_changed = false;
  std::vector<size_t> graphs_changed;
  for (const fs::path& file : changed) {
    bool is_graph = false;
    for (size_t i = 0; i < slots_.size(); ++i) {
      const std::vector<std::string> none;
      const std::vector<std::string>& fragments =
          slots_[i].instance ? slots_[i].instance->desc().included_files : none;
      if (slots_[i].file == file ||
          std::find(fragments.begin(), fragments.end(), file.string()) != fragments.end()) {
        is_graph = true;
        if (std::find(graphs_changed.begin(), graphs_changed.end(), i) == graphs_changed.end())
          graphs_changed.push_back(i);
      }
    }
    if (!is_graph) shaders_changed = true;
  }
  for (size_t i = 0; i < slots_.size(); ++i) {
    const bool graph_changed =
        std::find(graphs_changed.begin(), graphs_changed.end(), i) != graphs_changed.end();
    if (!graph_changed && !(shaders_changed && slots_[i].instance)) continue;
    if (!graph_changed && !slots_[i].instance) continue;
    // A graph not built yet is read when first shown; only errors of shown graphs matter now.
    if (!slots_[i].instance && i != active_) continue;
    if (build(i, graph_changed)) {
      report("reloaded " + slots_[i].file.string() + (shaders_changed ? " (shaders changed)" : ""),
             false);
    }
  }
}

void ViewerApp::apply_light_edits() {
  scene::Scene& scene = runtime_->scene();
  for (size_t i = 0; i < scene.lights.size() && i < light_edits_.size(); ++i) {
    const LightEdit& edit = light_edits_[i];
    if (!edit.edited) continue;
    scene::Light& light = scene.lights[i];
    light.position = edit.position;
    if (glm::length(edit.direction) > 1e-6f) light.direction = glm::normalize(edit.direction);
    light.intensity = std::max(edit.intensity, 0.0f);
    light.color = glm::max(edit.color, glm::vec3(0.0f));
  }
}

void ViewerApp::update_scene(runtime::FrameChanges& changes) {
  const double frame_seconds =
      script_.empty() ? std::clamp(frame_ms_.empty() ? 0.0 : frame_ms_.back() / 1000.0, 0.0, 0.1)
                      : kScriptFrameSeconds;
  bool advance = playing_;
  if (pending_steps_ > 0) {
    advance = true;
    --pending_steps_;
  }
  bool moved = false;
  if (advance && !runtime_->scene().animations.empty()) {
    time_ += playing_ ? frame_seconds : kScriptFrameSeconds;
    moved = runtime_->scene().animate(time_);
  }
  if (moved || lights_dirty_) {
    apply_light_edits();
    runtime_->upload_scene();
  }
  changes.camera = camera_.take_changed();
  changes.lights = moved || lights_dirty_;
  changes.geometry = moved;
  lights_dirty_ = false;
}

void ViewerApp::render_frame() {
  runtime::FrameChanges changes;
  update_scene(changes);
  const float aspect = static_cast<float>(options_.width) / static_cast<float>(options_.height);
  const runtime::FrameView view = runtime::frame_view(camera_.camera(), aspect);
  const bool two = (split_ || difference_) && slots_.size() > 1 && compare_ != active_;
  if (two && !slots_[compare_].instance && slots_[compare_].error.empty()) build(compare_, false);
  pair_shown_ = false;
  if (!two && pair_.instance) pair_ = SharedPair{};  // its memory goes with the split view
  if (two && inspect_.empty()) {
    if (runtime::GraphInstance* pair = shared_pair()) {
      const auto start = std::chrono::steady_clock::now();
      try {
        pair->render(view, time_, changes);
        pair_.timings.add_frame(pair->timings(), std::chrono::duration<double, std::milli>(
                                                     std::chrono::steady_clock::now() - start)
                                                     .count());
        pair_shown_ = true;
        compose();
        return;
      } catch (const std::exception& e) {
        pair_.instance.reset();
        pair_.error = e.what();
        report("the A/B pair runs apart: " + pair_.error, true);
      }
    }
  }
  std::vector<size_t> shown{active_};
  if (two) shown.push_back(compare_);
  for (size_t i : shown) {
    GraphSlot& slot = slots_[i];
    if (!slot.instance) continue;
    const auto start = std::chrono::steady_clock::now();
    try {
      slot.instance->render(view, time_, changes);
    } catch (const std::exception& e) {
      // A pass that fails while recording (e.g. a shader it compiles late) drops the build.
      slot.error = e.what();
      slot.instance.reset();
      report(slot.file.string() + ": " + e.what(), true);
      continue;
    }
    const double ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    slot.timings.add_frame(slot.instance->timings(), ms);
  }
  compose();
}

bool ViewerApp::edit_pair(size_t index, const std::string& key, const std::string& value) {
  if (!pair_.instance) return false;
  if (index != active_ && index != compare_) return true;  // not in the pair
  const std::string pass = key.substr(0, key.find('.'));
  // A shared pass edited on one side no longer runs alike on both: merge again.
  if (std::find(pair_.shared.begin(), pair_.shared.end(), pass) != pair_.shared.end()) {
    return false;
  }
  try {
    pair_.instance->set_param(index == active_ ? key : graph::kAbPrefix + key, value);
    return true;
  } catch (const std::exception&) {
    return false;
  }
}

runtime::GraphInstance* ViewerApp::shared_pair() {
  const GraphSlot& a = slots_[active_];
  const GraphSlot& b = slots_[compare_];
  if (!a.instance || !b.instance) return nullptr;
  if (pair_.a_build == a.build_id && pair_.b_build == b.build_id && pair_.edits == param_edits_) {
    return pair_.instance.get();
  }
  pair_ = SharedPair{};
  pair_.a_build = a.build_id;
  pair_.b_build = b.build_id;
  pair_.edits = param_edits_;
  try {
    const graph::AbMerge merge =
        graph::merge_for_ab(a.instance->compiled(), b.instance->compiled());
    runtime::GraphSettings settings;
    settings.width = options_.width;
    settings.height = options_.height;
    pair_.instance = std::make_unique<runtime::GraphInstance>(*runtime_, merge.desc, settings);
    pair_.shared = merge.shared_passes;
    report("A/B: " + std::to_string(merge.shared_passes.size()) + " shared passes run once, " +
               std::to_string(merge.b_passes.size()) + " of B's apart",
           false);
  } catch (const std::exception& e) {
    pair_.instance.reset();
    pair_.error = e.what();
    report("the A/B pair runs apart: " + pair_.error, true);
  }
  return pair_.instance.get();
}

void ViewerApp::compose() {
  GraphSlot& a = slots_[active_];
  if (!a.instance) return;
  const bool two = (split_ || difference_) && slots_.size() > 1 && compare_ != active_ &&
                   slots_[compare_].instance;
  try {
    if (!inspect_.empty() && a.instance->has_output(kInspectOutput)) {
      const int r = a.instance->compiled().find_resource(inspect_);
      const graph::ResourceInfo& info =
          a.instance->compiled().resources[static_cast<size_t>(r)].info;
      image::ImageRGBA32F whole = a.instance->read(kInspectOutput);
      const image::ImageRGBA32F slice =
          runtime::slice_of(info, whole.pixels, static_cast<uint32_t>(inspect_level_),
                            static_cast<uint32_t>(inspect_slice_));
      const bool display_referred =
          info.format == VK_FORMAT_R8G8B8A8_UNORM || info.format == VK_FORMAT_R8G8B8A8_SRGB;
      shown_linear_ = fit_nearest(slice, options_.width, options_.height);
      shown_display_ = inspect_to_display(shown_linear_, exposure_, display_referred, channels_);
      shown_caption_ = "inspect " + inspect_;
      return;
    }
    // A's outputs, or B's ("b/" in a shared pair): display and linear.
    const auto outputs = [](runtime::GraphInstance& graph, const std::string& prefix,
                            const std::string& name, image::ImageRGBA32F& display,
                            image::ImageRGBA32F& linear) {
      if (graph.has_output(prefix + "display")) {
        display = graph.read(prefix + "display");
        linear = graph.has_output(prefix + "linear") ? graph.read(prefix + "linear") : display;
      } else if (graph.has_output(prefix + "linear")) {
        // No display transform in this graph: show its radiance through the sRGB curve.
        linear = graph.read(prefix + "linear");
        display = inspect_to_display(linear, 0.0f, false, Channels::RGB);
      } else {
        throw std::runtime_error("graph '" + name +
                                 "' has neither a 'display' nor a 'linear' output to show");
      }
    };
    runtime::GraphInstance& source_a = pair_shown_ ? *pair_.instance : *a.instance;
    image::ImageRGBA32F display, linear;
    outputs(source_a, "", a.instance->desc().name, display, linear);
    shown_caption_ = a.instance->desc().name;
    if (two) {
      runtime::GraphInstance& b = *slots_[compare_].instance;
      image::ImageRGBA32F b_display, b_linear;
      if (pair_shown_) {
        outputs(*pair_.instance, graph::kAbPrefix, b.desc().name, b_display, b_linear);
      } else {
        outputs(b, "", b.desc().name, b_display, b_linear);
      }
      if (difference_) {
        display = runtime::difference(display, b_display, difference_gain_);
        linear = runtime::difference(linear, b_linear);
        shown_caption_ = "|" + a.instance->desc().name + " - " + b.desc().name + "|";
      } else {
        display = wipe(display, b_display, wipe_);
        linear = wipe(linear, b_linear, wipe_);
        shown_caption_ = a.instance->desc().name + " | " + b.desc().name;
      }
    }
    shown_display_ = std::move(display);
    shown_linear_ = std::move(linear);
  } catch (const std::exception& e) {
    report(std::string("showing the frame: ") + e.what(), true);
  }
}

void ViewerApp::screenshot(const fs::path& stem) {
  if (shown_display_.pixels.empty()) throw std::runtime_error("screenshot: no frame to write");
  if (stem.has_parent_path()) fs::create_directories(stem.parent_path());
  image::write_png(fs::path(stem.string() + ".png"), shown_display_);
  image::write_exr(fs::path(stem.string() + ".exr"), shown_linear_);
  report("wrote " + stem.string() + ".png and .exr (" + shown_caption_ + ")", false);
}

void ViewerApp::window_shot(const fs::path& file) {
  const std::vector<uint8_t>& bytes = presenter_->capture();
  if (bytes.empty()) throw std::runtime_error("window capture: this surface cannot be read back");
  image::ImageRGBA32F picture(presenter_->capture_width(), presenter_->capture_height());
  for (size_t i = 0; i < bytes.size(); ++i) picture.pixels[i] = bytes[i] / 255.0f;
  for (size_t i = 3; i < picture.pixels.size(); i += 4) picture.pixels[i] = 1.0f;
  if (file.has_parent_path()) fs::create_directories(file.parent_path());
  image::write_png(file, picture);
  report("wrote " + file.string() + " (the whole window)", false);
}

void ViewerApp::on_key(int key) {
  if (key >= GLFW_KEY_1 && key <= GLFW_KEY_9) {
    switch_graph(static_cast<size_t>(key - GLFW_KEY_1));
    return;
  }
  const float step = 0.05f * camera_.extent();
  switch (key) {
    case GLFW_KEY_TAB:
      switch_graph((active_ + 1) % slots_.size());
      break;
    case GLFW_KEY_F1:
      show_panel_ = !show_panel_;
      break;
    case GLFW_KEY_F2:
      split_ = !split_;
      if (split_ && slots_.size() < 2) report("split view needs two --graph files", true);
      break;
    case GLFW_KEY_F3:
      difference_ = !difference_;
      if (difference_ && slots_.size() < 2) report("the difference needs two --graph files", true);
      break;
    case GLFW_KEY_F5:
      for (size_t i = 0; i < slots_.size(); ++i)
        if (slots_[i].instance) build(i, true);
      break;
    case GLFW_KEY_F12:
      try {
        screenshot(fs::path(options_.out_dir) /
                   ("viewer-" + std::to_string(screenshot_counter_++)));
      } catch (const std::exception& e) {
        report(e.what(), true);
      }
      break;
    case GLFW_KEY_C:
      camera_.set_mode(camera_.mode() == CameraMode::Fly ? CameraMode::Orbit : CameraMode::Fly);
      break;
    case GLFW_KEY_R:
      camera_.reset(scene_camera_ >= 0
                        ? runtime_->scene().cameras[static_cast<size_t>(scene_camera_)]
                        : start_camera_,
                    camera_.extent());
      break;
    case GLFW_KEY_W:
      camera_.move({0, 0, 1}, step);
      break;
    case GLFW_KEY_S:
      camera_.move({0, 0, -1}, step);
      break;
    case GLFW_KEY_A:
      camera_.move({-1, 0, 0}, step);
      break;
    case GLFW_KEY_D:
      camera_.move({1, 0, 0}, step);
      break;
    case GLFW_KEY_Q:
      camera_.move({0, -1, 0}, step);
      break;
    case GLFW_KEY_E:
      camera_.move({0, 1, 0}, step);
      break;
    case GLFW_KEY_SPACE:
      playing_ = !playing_;
      break;
    case GLFW_KEY_PERIOD:
      ++pending_steps_;
      break;
    case GLFW_KEY_V:
      next_variant(active_);
      break;
    case GLFW_KEY_ESCAPE:
      quit_ = true;
      break;
    default:
      break;
  }
}

void ViewerApp::on_mouse_move(double x, double y) {
  const double dx = mouse_known_ ? x - mouse_x_ : 0.0;
  const double dy = mouse_known_ ? y - mouse_y_ : 0.0;
  mouse_x_ = x;
  mouse_y_ = y;
  mouse_known_ = true;
  if (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureMouse) return;
  const float radians_per_pixel = 0.005f;
  if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS) {
    camera_.set_mode(CameraMode::Fly);
    camera_.rotate(static_cast<float>(dx) * radians_per_pixel,
                   -static_cast<float>(dy) * radians_per_pixel);
  } else if (glfwGetMouseButton(window_, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS &&
             camera_.mode() == CameraMode::Orbit) {
    camera_.rotate(-static_cast<float>(dx) * radians_per_pixel,
                   static_cast<float>(dy) * radians_per_pixel);
  }
}

void ViewerApp::on_scroll(double dy) {
  if (camera_.mode() == CameraMode::Orbit) {
    camera_.zoom(dy > 0 ? 0.9f : 1.1f);
  } else {
    camera_.move({0, 0, dy > 0 ? 1.0f : -1.0f}, 0.05f * camera_.extent());
  }
}

void ViewerApp::handle_held_keys(double dt) {
  if (!script_.empty() || (ImGui::GetCurrentContext() && ImGui::GetIO().WantCaptureKeyboard)) {
    return;
  }
  glm::vec3 direction(0.0f);
  if (glfwGetKey(window_, GLFW_KEY_W) == GLFW_PRESS) direction.z += 1;
  if (glfwGetKey(window_, GLFW_KEY_S) == GLFW_PRESS) direction.z -= 1;
  if (glfwGetKey(window_, GLFW_KEY_D) == GLFW_PRESS) direction.x += 1;
  if (glfwGetKey(window_, GLFW_KEY_A) == GLFW_PRESS) direction.x -= 1;
  if (glfwGetKey(window_, GLFW_KEY_E) == GLFW_PRESS) direction.y += 1;
  if (glfwGetKey(window_, GLFW_KEY_Q) == GLFW_PRESS) direction.y -= 1;
  if (direction != glm::vec3(0.0f)) {
    camera_.move(direction, 0.5f * camera_.extent() * static_cast<float>(dt));
  }
}

int ViewerApp::run() {
  while (!quit_ && !glfwWindowShouldClose(window_)) {
    glfwPollEvents();
    if (!script_.empty() && !step_script()) break;
    const auto now = std::chrono::steady_clock::now();
    const double dt = std::chrono::duration<double>(now - last_frame_).count();
    last_frame_ = now;
    handle_held_keys(std::min(dt, 0.1));
    if (std::chrono::duration<double>(now - last_poll_).count() > 0.5) check_files();

    render_frame();
    const auto rendered = std::chrono::steady_clock::now();
    frame_ms_.push_back(static_cast<float>(dt * 1000.0));
    if (frame_ms_.size() > 120) frame_ms_.erase(frame_ms_.begin());

    ImGui_ImplVulkan_NewFrame();
    ImGui_ImplGlfw_NewFrame();
    ImGui::NewFrame();
    if (show_panel_) draw_panel();
    ImGui::Render();
    const std::vector<uint8_t> bytes = pack_rgba8(shown_display_, presenter_->bgr());
    if (pending_window_shot_) presenter_->request_capture();
    presenter_->present(bytes, shown_display_.width, shown_display_.height, ImGui::GetDrawData());
    ++frames_;
    (void)rendered;

    // Taken for the script, after the frame its earlier commands affect.
    try {
      if (pending_screenshot_) screenshot(*pending_screenshot_);
      if (pending_window_shot_) window_shot(*pending_window_shot_);
    } catch (const std::exception& e) {
      std::cerr << "voxgi-viewer: error: script: " << e.what() << "\n";
      exit_code_ = 1;
      quit_ = true;
    }
    pending_screenshot_.reset();
    pending_window_shot_.reset();
    if (script_frames_ > 0) --script_frames_;
  }
  if (options_.validation && runtime_->context().validation_message_count() > 0) {
    std::cerr << "voxgi-viewer: error: the validation layer reported "
              << runtime_->context().validation_message_count() << " message(s)\n";
    return 1;
  }
  return exit_code_;
}

bool ViewerApp::step_script() {
  while (script_frames_ == 0) {
    if (waiting_for_) {
      if (fs::exists(*waiting_for_)) {
        waiting_for_.reset();
      } else {
        if (std::chrono::steady_clock::now() > wait_deadline_) {
          std::cerr << "voxgi-viewer: error: script: timed out waiting for "
                    << waiting_for_->string() << "\n";
          exit_code_ = 1;
          return false;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
        return true;  // keep rendering while waiting
      }
    }
    if (script_pos_ >= script_.size()) return !quit_;
    const ScriptCommand& command = script_[script_pos_++];
    try {
      run_command(command);
    } catch (const std::exception& e) {
      std::cerr << "voxgi-viewer: error: " << *options_.script << ":" << command.line << ": "
                << command.name << ": " << e.what() << "\n";
      exit_code_ = 1;
      return false;
    }
    if (quit_) return false;
  }
  return true;
}

void ViewerApp::run_command(const ScriptCommand& command) {
  const std::string& name = command.name;
  const std::vector<std::string>& args = command.args;
  auto number = [&](size_t i) -> double {
    try {
      size_t used = 0;
      const double v = std::stod(args[i], &used);
      if (used != args[i].size() || !std::isfinite(v)) throw std::invalid_argument("");
      return v;
    } catch (const std::exception&) {
      throw std::invalid_argument("'" + args[i] + "' is not a number");
    }
  };
  auto on_off = [&](size_t i) {
    if (args[i] == "on") return true;
    if (args[i] == "off") return false;
    throw std::invalid_argument("'" + args[i] + "': expected on or off");
  };
  if (name == "frames") {
    const double n = number(0);
    if (n < 1 || n > 100000) throw std::invalid_argument("frames: expected 1 to 100000");
    script_frames_ = static_cast<int>(n);
  } else if (name == "key") {
    on_key(key_code(args[0]));
  } else if (name == "set") {
    const size_t eq = args[0].find('=');
    set_param(active_, args[0].substr(0, eq), args[0].substr(eq + 1));
  } else if (name == "graph") {
    const double n = number(0);
    if (n < 1 || n > static_cast<double>(slots_.size())) {
      throw std::invalid_argument("graph " + args[0] + ": expected 1 to " +
                                  std::to_string(slots_.size()));
    }
    switch_graph(static_cast<size_t>(n) - 1);
    if (!slots_[static_cast<size_t>(n) - 1].instance)
      throw std::runtime_error("the graph failed to build");
  } else if (name == "variant") {
    set_variant(active_, args[0] == "none" ? std::string() : args[0]);
  } else if (name == "split") {
    split_ = on_off(0);
  } else if (name == "compare") {
    const double n = number(0);
    if (n < 1 || n > static_cast<double>(slots_.size())) {
      throw std::invalid_argument("compare " + args[0] + ": expected 1 to " +
                                  std::to_string(slots_.size()));
    }
    compare_ = static_cast<size_t>(n) - 1;
  } else if (name == "wipe") {
    wipe_ = std::clamp(static_cast<float>(number(0)), 0.0f, 1.0f);
  } else if (name == "diff") {
    difference_ = on_off(0);
    if (args.size() > 1) difference_gain_ = static_cast<float>(number(1));
  } else if (name == "inspect") {
    if (args[0] == "off") {
      set_inspect("");
    } else {
      const graph::CompiledGraph& compiled = slots_[active_].instance->compiled();
      const int r = compiled.find_resource(args[0]);
      if (r < 0 ||
          compiled.resources[static_cast<size_t>(r)].info.kind == graph::ResourceKind::Buffer) {
        throw std::invalid_argument("the graph has no image resource '" + args[0] + "'");
      }
      set_inspect(args[0]);
      if (inspect_ != args[0]) throw std::runtime_error("cannot inspect '" + args[0] + "'");
      if (args.size() > 1) inspect_level_ = static_cast<int>(number(1));
      if (args.size() > 2) inspect_slice_ = static_cast<int>(number(2));
    }
  } else if (name == "exposure") {
    exposure_ = static_cast<float>(number(0));
  } else if (name == "camera") {
    if (args[0] == "fly") {
      camera_.set_mode(CameraMode::Fly);
    } else if (args[0] == "orbit") {
      camera_.set_mode(CameraMode::Orbit);
    } else {
      const scene::Scene& scene = runtime_->scene();
      bool found = false;
      for (size_t i = 0; i < scene.cameras.size(); ++i) {
        if (scene.cameras[i].name != args[0]) continue;
        scene_camera_ = static_cast<int>(i);
        camera_.reset(scene.cameras[i], camera_.extent());
        found = true;
      }
      if (!found) runtime::choose_camera(scene, args[0]);  // throws listing the cameras
    }
  } else if (name == "move") {
    camera_.move({number(0), number(1), number(2)}, 1.0f);
  } else if (name == "turn") {
    camera_.rotate(glm::radians(static_cast<float>(number(0))),
                   glm::radians(static_cast<float>(number(1))));
  } else if (name == "light") {
    const double index = number(0);
    if (index < 0 || index >= static_cast<double>(light_edits_.size())) {
      throw std::invalid_argument("light " + args[0] + ": the scene has " +
                                  std::to_string(light_edits_.size()) + " light(s)");
    }
    const size_t i = static_cast<size_t>(index);
    LightEdit& edit = light_edits_[i];
    if (!edit.edited) {
      const scene::Light& light = runtime_->scene().lights[i];
      edit = {true, light.position, light.direction, light.intensity, light.color};
    }
    const std::string& what = args[1];
    if (what == "intensity" && args.size() == 3) {
      edit.intensity = static_cast<float>(number(2));
      if (edit.intensity < 0) throw std::invalid_argument("intensity must not be negative");
    } else if ((what == "color" || what == "position" || what == "direction") && args.size() == 5) {
      const glm::vec3 v(number(2), number(3), number(4));
      if (what == "color") edit.color = v;
      if (what == "position") edit.position = v;
      if (what == "direction") edit.direction = v;
    } else {
      throw std::invalid_argument(
          "expected: light INDEX intensity V | color R G B | position X Y "
          "Z | direction X Y Z");
    }
    lights_dirty_ = true;
  } else if (name == "play") {
    playing_ = true;
  } else if (name == "pause") {
    playing_ = false;
  } else if (name == "step") {
    const double n = args.empty() ? 1.0 : number(0);
    if (n < 1 || n > 100000) throw std::invalid_argument("step: expected 1 to 100000 frames");
    pending_steps_ += static_cast<int>(n);
    script_frames_ = std::max(script_frames_, static_cast<int>(n));  // one step per frame
  } else if (name == "screenshot") {
    pending_screenshot_ = fs::path(args[0]);
    script_frames_ = 1;  // taken after the next frame, so earlier commands show in it
  } else if (name == "window-shot") {
    pending_window_shot_ = fs::path(args[0]);
    script_frames_ = 1;
  } else if (name == "timings") {
    if (pair_shown_) {
      std::string shared;
      for (const std::string& pass : pair_.shared) shared += (shared.empty() ? "" : " ") + pass;
      pair_.timings.write_json(args[0],
                               {{"graph", pair_.instance->desc().name}, {"shared_passes", shared}});
    } else {
      slots_[active_].timings.write_json(args[0], {{"graph", slots_[active_].file.string()}});
    }
    report("wrote " + args[0], false);
  } else if (name == "edit-check") {
    check_files();
  } else if (name == "wait-for") {
    waiting_for_ = fs::path(args[0]);
    const double seconds = args.size() > 1 ? number(1) : 60.0;
    wait_deadline_ = std::chrono::steady_clock::now() +
                     std::chrono::milliseconds(static_cast<int64_t>(seconds * 1000.0));
  } else if (name == "window") {
    const double w = number(0), h = number(1);
    if (w < 64 || h < 64 || w > 8192 || h > 8192) {
      throw std::invalid_argument("window: expected sizes from 64 to 8192");
    }
    // The image keeps its size; the swapchain follows the window on the next frame.
    glfwSetWindowSize(window_, static_cast<int>(w), static_cast<int>(h));
    script_frames_ = std::max(script_frames_, 1);
  } else if (name == "open") {
    static const std::set<std::string> sections = {"graphs",    "timings",    "camera", "lights",
                                                   "animation", "parameters", "inspect"};
    if (!sections.count(args[0])) throw std::invalid_argument("no panel section '" + args[0] + "'");
    open_sections_.insert(args[0]);
  } else if (name == "quit") {
    quit_ = true;
  }
}

}  // namespace voxgi::viewer
