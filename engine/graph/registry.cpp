#include <algorithm>
#include <stdexcept>

#include "engine/graph/pass.hpp"

namespace voxgi::graph {

void Registry::add(PassTypeInfo info, PassFactory factory) {
  if (info.type.empty()) throw std::invalid_argument("pass type registered with an empty name");
  if (find(info.type)) {
    throw std::invalid_argument("pass type '" + info.type + "' is already registered");
  }
  if (!factory) {
    throw std::invalid_argument("pass type '" + info.type + "' registered without a factory");
  }
  // Indirect arguments are read by commands from buffers: an image or an output there is a bug
  // of the type's declaration, found when its plugin registers it.
  const auto check_indirect = [&](const std::vector<SlotSpec>& slots, bool inputs) {
    for (const SlotSpec& slot : slots) {
      if (slot.access != Access::IndirectRead) continue;
      if (!inputs || slot.kinds != kinds(ResourceKind::Buffer)) {
        throw std::invalid_argument("pass type '" + info.type + "' slot '" + slot.name +
                                    "': indirect access is for input slots of buffers only");
      }
    }
  };
  check_indirect(info.inputs, true);
  check_indirect(info.outputs, false);
  entries_.push_back(Entry{std::move(info), std::move(factory)});
}

const PassTypeInfo* Registry::find(std::string_view type) const {
  for (const Entry& e : entries_) {
    if (e.info.type == type) return &e.info;
  }
  return nullptr;
}

std::unique_ptr<Pass> Registry::create(std::string_view type) const {
  for (const Entry& e : entries_) {
    if (e.info.type == type) {
      std::unique_ptr<Pass> pass = e.factory();
      if (!pass) throw std::runtime_error("pass type '" + e.info.type + "' factory returned null");
      return pass;
    }
  }
  throw std::invalid_argument("unknown pass type '" + std::string(type) + "'");
}

std::vector<const PassTypeInfo*> Registry::all() const {
  std::vector<const PassTypeInfo*> list;
  for (const Entry& e : entries_) list.push_back(&e.info);
  std::sort(list.begin(), list.end(),
            [](const PassTypeInfo* a, const PassTypeInfo* b) { return a->type < b->type; });
  return list;
}

}  // namespace voxgi::graph
