// The viewer's Dear ImGui panel: graphs and A/B, camera, lights, animation, parameters from
// the registry's metadata, timings, and resource inspection.

#include <GLFW/glfw3.h>
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "apps/viewer/viewer_app.hpp"
#include "engine/graph/compiler.hpp"
#include "engine/runtime/output_files.hpp"

namespace voxgi::viewer {
namespace {

constexpr float kPanelWidth = 440.0f;

}  // namespace

bool ViewerApp::header(const char* label, const char* section, bool open_by_default) {
  if (open_sections_.count(section)) ImGui::SetNextItemOpen(true);
  return ImGui::CollapsingHeader(label, open_by_default ? ImGuiTreeNodeFlags_DefaultOpen : 0);
}

void ViewerApp::draw_panel() {
  // The image sits at the top-left at 1:1; the panel fills the rest of the window.
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImDrawList* background = ImGui::GetBackgroundDrawList();
  if (split_ && !difference_ && slots_.size() > 1 && inspect_.empty()) {
    const float x = wipe_ * static_cast<float>(options_.width);
    background->AddLine(ImVec2(x, 0), ImVec2(x, static_cast<float>(options_.height)),
                        IM_COL32(255, 255, 255, 160));
  }
  const float panel_x = std::min(static_cast<float>(options_.width), display.x - 200.0f);
  ImGui::SetNextWindowPos(ImVec2(std::max(panel_x, 0.0f), 0.0f));
  ImGui::SetNextWindowSize(ImVec2(std::max(display.x - panel_x, kPanelWidth * 0.5f), display.y));
  ImGui::Begin("voxgi", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse);

  const std::vector<float> frame = frame_ms_;
  const float last_ms = frame.empty() ? 0.0f : frame.back();
  ImGui::Text("%s", runtime_->context().device_name().c_str());
  ImGui::Text("%s  %ux%u  frame %.1f ms (%.0f fps)", runtime_->scene().source.c_str(),
              options_.width, options_.height, last_ms, last_ms > 0 ? 1000.0f / last_ms : 0.0f);
  if (!frame.empty()) {
    ImGui::PlotLines("##frame", frame.data(), static_cast<int>(frame.size()), 0, "frame ms", 0.0f,
                     FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 40));
  }
  ImGui::TextUnformatted(shown_caption_.c_str());
  if (!message_.empty()) {
    ImGui::PushStyleColor(ImGuiCol_Text, message_is_error_ ? IM_COL32(255, 110, 110, 255)
                                                           : IM_COL32(160, 220, 160, 255));
    ImGui::TextWrapped("%s", message_.c_str());
    ImGui::PopStyleColor();
  }

  if (header("Graphs", "graphs", true)) {
    for (size_t i = 0; i < slots_.size(); ++i) {
      char label[512];
      std::snprintf(label, sizeof label, "%zu  %s", i + 1, slot_label(i).c_str());
      if (ImGui::RadioButton(label, active_ == i)) switch_graph(i);
      if (!slots_[i].error.empty()) {
        ImGui::PushStyleColor(ImGuiCol_Text, IM_COL32(255, 110, 110, 255));
        ImGui::TextWrapped("%s", slots_[i].error.c_str());
        ImGui::PopStyleColor();
      }
    }
    if (slots_.size() > 1) {
      ImGui::Checkbox("split A|B (F2)", &split_);
      ImGui::SameLine();
      ImGui::Checkbox("difference (F3)", &difference_);
      int b = static_cast<int>(compare_) + 1;
      if (ImGui::SliderInt("B graph", &b, 1, static_cast<int>(slots_.size()))) {
        compare_ = static_cast<size_t>(b - 1);
      }
      ImGui::SliderFloat("wipe", &wipe_, 0.0f, 1.0f);
      ImGui::SliderFloat("difference gain", &difference_gain_, 1.0f, 64.0f, "%.1f",
                         ImGuiSliderFlags_Logarithmic);
    }
    if (ImGui::Button("reload (F5)")) {
      for (size_t i = 0; i < slots_.size(); ++i)
        if (slots_[i].instance) build(i, true);
    }
    ImGui::SameLine();
    if (ImGui::Button("screenshot (F12)")) on_key(GLFW_KEY_F12);
  }

  if (header("Timings", "timings", true)) {
    if (pair_shown_) {
      // One merged graph: B's own passes are "b/...", the shared ones ran once for both.
      std::string shared;
      for (const std::string& pass : pair_.shared) shared += (shared.empty() ? "" : ", ") + pass;
      ImGui::TextWrapped("A/B as one graph; shared, run once: %s",
                         shared.empty() ? "none" : shared.c_str());
      draw_timings_table(pair_.timings, "pair");
    } else {
      draw_timings_table(slots_[active_].timings, "a");
      if ((split_ || difference_) && slots_.size() > 1 && compare_ != active_ &&
          slots_[compare_].instance) {
        ImGui::Text("B: %s", slot_label(compare_).c_str());
        draw_timings_table(slots_[compare_].timings, "b");
      }
    }
  }

  if (header("Camera", "camera", false)) {
    int mode = camera_.mode() == CameraMode::Fly ? 0 : 1;
    if (ImGui::RadioButton("fly", mode == 0)) camera_.set_mode(CameraMode::Fly);
    ImGui::SameLine();
    if (ImGui::RadioButton("orbit (C)", mode == 1)) camera_.set_mode(CameraMode::Orbit);
    const scene::Scene& scene = runtime_->scene();
    const char* current = scene_camera_ >= 0
                              ? scene.cameras[static_cast<size_t>(scene_camera_)].name.c_str()
                              : "start camera";
    if (ImGui::BeginCombo("scene camera", current)) {
      if (ImGui::Selectable("start camera", scene_camera_ < 0)) {
        scene_camera_ = -1;
        camera_.reset(start_camera_, camera_.extent());
      }
      for (size_t i = 0; i < scene.cameras.size(); ++i) {
        const std::string label =
            scene.cameras[i].name.empty() ? "camera " + std::to_string(i) : scene.cameras[i].name;
        if (ImGui::Selectable(label.c_str(), scene_camera_ == static_cast<int>(i))) {
          scene_camera_ = static_cast<int>(i);
          camera_.reset(scene.cameras[i], camera_.extent());
        }
      }
      ImGui::EndCombo();
    }
    glm::vec3 position = camera_.position();
    if (ImGui::DragFloat3("position", &position.x, 0.01f * camera_.extent())) {
      camera_.set_position(position);
    }
  }

  draw_lights_panel();

  if (!runtime_->scene().animations.empty() && header("Animation", "animation", false)) {
    ImGui::Checkbox("play (Space)", &playing_);
    ImGui::SameLine();
    if (ImGui::Button("step (.)")) ++pending_steps_;
    ImGui::Text("time %.3f s", time_);
  }

  if (header("Parameters", "parameters", false)) draw_params_panel(active_);
  draw_inspect_panel();
  ImGui::End();
  open_sections_.clear();
}

void ViewerApp::draw_timings_table(const runtime::TimingsHistory& history, const std::string& id) {
  const std::vector<float> totals = history.gpu_totals_ms();
  if (!totals.empty()) {
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "GPU %.2f ms", totals.back());
    ImGui::PlotLines(("##gpu" + id).c_str(), totals.data(), static_cast<int>(totals.size()), 0,
                     overlay, 0.0f, FLT_MAX, ImVec2(ImGui::GetContentRegionAvail().x, 40));
  }
  if (!ImGui::BeginTable(("timings" + id).c_str(), 4,
                         ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV)) {
    return;
  }
  ImGui::TableSetupColumn("pass");
  ImGui::TableSetupColumn("GPU ms");
  ImGui::TableSetupColumn("CPU ms");
  ImGui::TableSetupColumn("skipped");
  ImGui::TableHeadersRow();
  for (const runtime::PassTimingSummary& s : history.summary()) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(s.pass.c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", s.type.c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", s.gpu_ms_median);
    ImGui::TableNextColumn();
    ImGui::Text("%.3f", s.cpu_ms_median);
    ImGui::TableNextColumn();
    ImGui::Text("%u", s.skipped);
    if (!s.skip_reason.empty() && ImGui::IsItemHovered()) {
      ImGui::SetTooltip("%s", s.skip_reason.c_str());
    }
  }
  ImGui::EndTable();
}

void ViewerApp::draw_params_panel(size_t slot) {
  if (!slots_[slot].instance) return;
  runtime::GraphInstance& graph = *slots_[slot].instance;
  // Copied: a non-live change rebuilds the pass, and set_param edits the compiled params.
  const std::vector<graph::CompiledPass> passes = graph.compiled().passes;
  for (const graph::CompiledPass& pass : passes) {
    if (!pass.type_info || pass.type_info->params.empty()) continue;
    if (open_sections_.count("parameters")) ImGui::SetNextItemOpen(true);
    if (!ImGui::TreeNode(pass.name.c_str(), "%s  (%s)", pass.name.c_str(), pass.type.c_str())) {
      continue;
    }
    for (const graph::ParamSpec& spec : pass.type_info->params) {
      const auto found = pass.params.find(spec.name);
      if (found == pass.params.end()) continue;
      const std::string key = pass.name + "." + spec.name;
      const std::string label = spec.name + (spec.live ? "" : " *") + "##" + key;
      double value = found->second.number;
      std::string text;
      bool changed = false;
      switch (spec.type) {
        case graph::ParamType::Bool: {
          bool on = value != 0.0;
          changed = ImGui::Checkbox(label.c_str(), &on);
          text = on ? "true" : "false";
          break;
        }
        case graph::ParamType::Int: {
          int v = static_cast<int>(value);
          const int lo = static_cast<int>(std::max(spec.min, -1e9));
          const int hi = static_cast<int>(std::min(spec.max, 1e9));
          changed = hi - lo <= 4096 ? ImGui::SliderInt(label.c_str(), &v, lo, hi)
                                    : ImGui::DragInt(label.c_str(), &v, 1.0f, lo, hi);
          text = std::to_string(v);
          break;
        }
        case graph::ParamType::Float: {
          float v = static_cast<float>(value);
          const float lo = static_cast<float>(spec.min), hi = static_cast<float>(spec.max);
          changed = hi - lo <= 1000.0f
                        ? ImGui::SliderFloat(label.c_str(), &v, lo, hi, "%.4g")
                        : ImGui::DragFloat(label.c_str(), &v, std::max(1e-3f, std::abs(v) * 0.01f),
                                           lo, hi, "%.4g");
          text = graph::format_number(v);
          break;
        }
        case graph::ParamType::Enum: {
          int index = static_cast<int>(value);
          const char* current = index >= 0 && index < static_cast<int>(spec.choices.size())
                                    ? spec.choices[static_cast<size_t>(index)].c_str()
                                    : "?";
          if (ImGui::BeginCombo(label.c_str(), current)) {
            for (size_t c = 0; c < spec.choices.size(); ++c) {
              if (ImGui::Selectable(spec.choices[c].c_str(), index == static_cast<int>(c))) {
                text = spec.choices[c];
                changed = true;
              }
            }
            ImGui::EndCombo();
          }
          break;
        }
      }
      if (ImGui::IsItemHovered()) {
        if (spec.type == graph::ParamType::Int || spec.type == graph::ParamType::Float) {
          ImGui::SetTooltip("%s\n%s in [%g, %g]%s", spec.doc.c_str(),
                            graph::param_type_name(spec.type), spec.min, spec.max,
                            spec.live ? "" : "\n* re-runs the pass's setup");
        } else {
          ImGui::SetTooltip("%s\n%s%s", spec.doc.c_str(), graph::param_type_name(spec.type),
                            spec.live ? "" : "\n* re-runs the pass's setup");
        }
      }
      if (changed) {
        try {
          set_param(slot, key, text);
        } catch (const std::exception&) {
          // Reported in the panel by set_param.
        }
      }
    }
    ImGui::TreePop();
  }
}

void ViewerApp::draw_lights_panel() {
  scene::Scene& scene = runtime_->scene();
  if (scene.lights.empty() || !header("Lights", "lights", false)) return;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const scene::Light& light = scene.lights[i];
    const std::string id = "light " + std::to_string(i) + " " + light.name;
    if (open_sections_.count("lights")) ImGui::SetNextItemOpen(true);
    if (!ImGui::TreeNode(id.c_str())) continue;
    LightEdit& edit = light_edits_[i];
    if (!edit.edited) {
      edit.position = light.position;
      edit.direction = light.direction;
      edit.intensity = light.intensity;
      edit.color = light.color;
    }
    bool changed = false;
    if (light.type != scene::LightType::Directional) {
      changed |= ImGui::DragFloat3("position", &edit.position.x, 0.01f * camera_.extent());
    }
    if (light.type != scene::LightType::Point) {
      changed |= ImGui::DragFloat3("direction", &edit.direction.x, 0.01f, -1.0f, 1.0f);
    }
    changed |=
        ImGui::DragFloat("intensity", &edit.intensity, std::max(0.01f, edit.intensity * 0.01f),
                         0.0f, 1e7f, "%.4g", ImGuiSliderFlags_Logarithmic);
    changed |= ImGui::ColorEdit3("colour", &edit.color.x);
    if (changed) {
      edit.edited = true;
      lights_dirty_ = true;
    }
    ImGui::TreePop();
  }
}

void ViewerApp::draw_inspect_panel() {
  if (!header("Inspect", "inspect", false) || !slots_[active_].instance) return;
  const graph::CompiledGraph& compiled = slots_[active_].instance->compiled();
  if (ImGui::BeginCombo("resource", inspect_.empty() ? "(graph output)" : inspect_.c_str())) {
    std::string chosen;
    bool picked = false;
    if (ImGui::Selectable("(graph output)", inspect_.empty())) {
      picked = true;
    }
    for (const graph::CompiledResource& r : compiled.resources) {
      if (r.info.kind == graph::ResourceKind::Buffer || r.physical < 0) continue;
      if (ImGui::Selectable(r.info.name.c_str(), r.info.name == inspect_)) {
        chosen = r.info.name;
        picked = true;
      }
    }
    ImGui::EndCombo();
    if (picked && chosen != inspect_) set_inspect(chosen);
  }
  if (!inspect_.empty()) {
    const int r = compiled.find_resource(inspect_);
    if (r >= 0) {
      const graph::ResourceInfo& info = compiled.resources[static_cast<size_t>(r)].info;
      ImGui::Text("%s %ux%ux%u %s", graph::kind_name(info.kind).c_str(), info.extent.width,
                  info.extent.height, info.extent.depth, graph::format_name(info.format).c_str());
      const int levels = static_cast<int>(runtime::level_count(info));
      const int slices = static_cast<int>(runtime::slice_count(info));
      if (levels > 1) ImGui::SliderInt("clipmap level", &inspect_level_, 0, levels - 1);
      if (slices > 1) ImGui::SliderInt("slice", &inspect_slice_, 0, slices - 1);
      if (info.array_layers > 1) ImGui::Text("layer 0 of %u", info.array_layers);
    }
  }
  ImGui::SliderFloat("exposure (EV)", &exposure_, -16.0f, 16.0f, "%.1f");
  int channels = static_cast<int>(channels_);
  const char* names[] = {"RGB", "R", "G", "B", "A"};
  if (ImGui::Combo("channels", &channels, names, 5)) channels_ = static_cast<Channels>(channels);
}

}  // namespace voxgi::viewer
