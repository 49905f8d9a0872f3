#pragma once
// Human and machine views of a graph: `voxgi graph explain`, one JSON file per compile phase,
// and Graphviz DOT.

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "engine/graph/compiler.hpp"
#include "engine/graph/graph_desc.hpp"

namespace voxgi::graph {

std::string explain(const CompiledGraph& graph);

nlohmann::json desc_to_json(const GraphDesc& desc);            // parsed
nlohmann::json resolved_to_json(const CompiledGraph& graph);   // validated: params, bindings
nlohmann::json culled_to_json(const CompiledGraph& graph);     // culled passes and reasons
nlohmann::json schedule_to_json(const CompiledGraph& graph);   // order and dependencies
nlohmann::json barriers_to_json(const CompiledGraph& graph);   // per pass, frame start/end
nlohmann::json resources_to_json(const CompiledGraph& graph);  // lifetimes, sharing, memory

std::string to_dot(const CompiledGraph& graph);

// Writes 1-parsed.json, 2-resolved.json, 3-culled.json, 4-schedule.json, 5-barriers.json,
// 6-resources.json and graph.dot into dir (created if needed). Throws std::runtime_error.
void dump_phases(const GraphDesc& desc, const CompiledGraph& graph,
                 const std::filesystem::path& dir);

// Names for Vulkan enums as they appear in dumps ("SHADER_READ_ONLY_OPTIMAL").
std::string layout_name(VkImageLayout layout);
std::string stages_text(VkPipelineStageFlags2 stages);
std::string access_text(VkAccessFlags2 access);

}  // namespace voxgi::graph
