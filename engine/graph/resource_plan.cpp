#include "engine/graph/resource_plan.hpp"

#include <algorithm>
#include <map>
#include <optional>
#include <utility>

namespace voxgi::graph {

uint64_t estimate_bytes(const ResourceInfo& info) {
  if (info.kind == ResourceKind::Buffer) return info.buffer_size;
  uint64_t texels = 0;
  for (uint32_t m = 0; m < info.mip_levels; ++m) {
    texels += uint64_t{std::max(1u, info.extent.width >> m)} *
              std::max(1u, info.extent.height >> m) * std::max(1u, info.extent.depth >> m);
  }
  return texels * format_texel_bytes(info.format) * info.array_layers;
}

VkImageUsageFlags image_usage_for(Access access) {
  switch (access) {
    case Access::Sampled:
      return VK_IMAGE_USAGE_SAMPLED_BIT;
    case Access::StorageRead:
    case Access::StorageWrite:
    case Access::StorageReadWrite:
      return VK_IMAGE_USAGE_STORAGE_BIT;
    case Access::ColorAttachment:
      return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    case Access::DepthAttachment:
      return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    case Access::UniformRead:
    case Access::IndirectRead:
      return 0;
    case Access::TransferRead:
      return VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferWrite:
      return VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  }
  return 0;
}

VkBufferUsageFlags buffer_usage_for(Access access) {
  switch (access) {
    case Access::UniformRead:
      return VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT;
    case Access::TransferRead:
      return VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    case Access::TransferWrite:
      return VK_BUFFER_USAGE_TRANSFER_DST_BIT;
    case Access::IndirectRead:
      return VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
    default:
      return VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  }
}

namespace {

constexpr VkAccessFlags2 kWriteAccess =
    VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
    VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT;

struct Need {
  ResourceState state;
  bool reads = false;
  bool writes = false;
};

bool covered(const SyncTrack& t, const ResourceState& s) {
  return std::any_of(t.visible.begin(), t.visible.end(), [&](const auto& v) {
    return (s.stages & ~v.first) == 0 && (s.access & ~v.second) == 0;
  });
}

// The barrier (if any) taking `t` to `need`, and the track afterwards.
std::optional<Barrier> transition(SyncTrack& t, const Need& need, bool discard, bool is_buffer) {
  const ResourceState& s = need.state;
  const bool layout_change = !is_buffer && (discard || s.layout != t.layout);
  std::optional<Barrier> barrier;
  auto make = [&](VkPipelineStageFlags2 src_stages, VkAccessFlags2 src_access) {
    Barrier b;
    b.is_buffer = is_buffer;
    b.src_stages = src_stages;
    b.src_access = src_access;
    b.dst_stages = s.stages;
    b.dst_access = s.access;
    b.old_layout =
        is_buffer ? VK_IMAGE_LAYOUT_UNDEFINED : (discard ? VK_IMAGE_LAYOUT_UNDEFINED : t.layout);
    b.new_layout = is_buffer ? VK_IMAGE_LAYOUT_UNDEFINED : s.layout;
    barrier = b;
  };
  const VkPipelineStageFlags2 before = t.write_stages | t.read_stages;
  if (layout_change || need.writes) {
    if (layout_change || before != 0) make(before, t.write_access);
    if (need.writes) {
      t.write_stages = s.stages;
      t.write_access = s.access & kWriteAccess;
      t.read_stages = need.reads ? s.stages : 0;
      t.visible.clear();
      if (layout_change) t.visible.push_back({s.stages, s.access & ~kWriteAccess});
    } else {
      // A layout transition is a write, made visible to this access only.
      t.write_stages = s.stages;
      t.write_access = 0;
      t.read_stages = s.stages;
      t.visible = {{s.stages, s.access}};
    }
    t.layout = s.layout;
    return barrier;
  }
  if (t.write_stages != 0 && !covered(t, s)) {
    make(t.write_stages, t.write_access);
    t.visible.push_back({s.stages, s.access});
  }
  t.read_stages |= s.stages;
  return barrier;
}

bool mergeable(const Barrier& a, const Barrier& b) {
  return a.resource == b.resource && a.is_buffer == b.is_buffer && a.is_global == b.is_global &&
         a.base_mip + a.mip_count == b.base_mip && a.src_stages == b.src_stages &&
         a.src_access == b.src_access && a.dst_stages == b.dst_stages &&
         a.dst_access == b.dst_access && a.old_layout == b.old_layout &&
         a.new_layout == b.new_layout;
}

void append_merged(std::vector<Barrier>& list, const Barrier& b) {
  if (!list.empty() && mergeable(list.back(), b)) {
    list.back().mip_count += b.mip_count;
  } else {
    list.push_back(b);
  }
}

void plan_lifetimes_and_usage(CompiledGraph& g) {
  g.history_copies.clear();
  for (size_t s = 0; s < g.passes.size(); ++s) {
    for (const SlotBinding& b : g.passes[s].bindings) {
      if (b.resource < 0) continue;
      CompiledResource& r = g.resources[static_cast<size_t>(b.resource)];
      const int index = static_cast<int>(s);
      if (r.first_pass < 0) r.first_pass = index;
      r.last_pass = std::max(r.last_pass, index);
      if (r.info.kind == ResourceKind::Buffer) {
        r.buffer_usage |= buffer_usage_for(b.spec->access);
      } else {
        r.image_usage |= image_usage_for(b.spec->access);
      }
    }
  }
  for (CompiledResource& r : g.resources) {
    if (r.first_pass < 0) continue;
    // The compiler makes sure a transient's first use writes it.
    r.carries_contents = r.info.persistent;
    if (r.info.kind == ResourceKind::Buffer) {
      // Transfer destination: persistent buffers are cleared on creation.
      r.buffer_usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
      if (r.is_output) r.buffer_usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    } else {
      // Sampled so that viewers can show any image; transfer dst for clears.
      r.image_usage |= VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
      if (r.is_output) r.image_usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    }
    // Outputs are read back after the last pass.
    if (r.is_output) r.last_pass = static_cast<int>(g.passes.size());
  }
  // Frame history: a read previous version is copied from the current one as the frame ends,
  // so both live to the end. Without a live reader, or without a live writer of the original
  // (the copy then keeps its zeros), there is no copy.
  for (CompiledResource& twin : g.resources) {
    if (twin.history_of < 0 || twin.first_pass < 0) continue;
    CompiledResource& original = g.resources[static_cast<size_t>(twin.history_of)];
    if (original.first_pass < 0) continue;
    const int end = static_cast<int>(g.passes.size());
    original.last_pass = twin.last_pass = end;
    if (original.info.kind == ResourceKind::Buffer) {
      original.buffer_usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
    } else {
      original.image_usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    }
    g.history_copies.push_back({twin.history_of, static_cast<int>(&twin - g.resources.data())});
  }
}

void plan_physical(CompiledGraph& g, bool alias_transients) {
  std::vector<size_t> by_first_use;
  for (size_t i = 0; i < g.resources.size(); ++i) {
    if (g.resources[i].first_pass >= 0) by_first_use.push_back(i);
  }
  std::stable_sort(by_first_use.begin(), by_first_use.end(), [&](size_t a, size_t b) {
    return g.resources[a].first_pass < g.resources[b].first_pass;
  });
  std::vector<int> busy_until;  // per physical: the last pass of its latest sharer
  std::vector<bool> shareable;
  for (size_t i : by_first_use) {
    CompiledResource& r = g.resources[i];
    const bool can_share = alias_transients && !r.carries_contents && !r.is_output;
    int chosen = -1;
    if (can_share) {
      for (size_t p = 0; p < g.physical.size(); ++p) {
        if (shareable[p] && busy_until[p] < r.first_pass &&
            same_description(g.physical[p].info, r.info)) {
          chosen = static_cast<int>(p);
          break;
        }
      }
    }
    if (chosen < 0) {
      PhysicalResource p;
      p.info = r.info;
      p.bytes = r.bytes;
      p.carries_contents = r.carries_contents;
      g.physical.push_back(p);
      busy_until.push_back(-1);
      shareable.push_back(can_share);
      chosen = static_cast<int>(g.physical.size() - 1);
    }
    PhysicalResource& p = g.physical[static_cast<size_t>(chosen)];
    p.resources.push_back(static_cast<int>(i));
    p.image_usage |= r.image_usage;
    p.buffer_usage |= r.buffer_usage;
    busy_until[static_cast<size_t>(chosen)] = r.last_pass;
    r.physical = chosen;
  }
  // Every sharer needs every usage of the allocation it lives in.
  for (CompiledResource& r : g.resources) {
    if (r.physical < 0) continue;
    r.image_usage = g.physical[static_cast<size_t>(r.physical)].image_usage;
    r.buffer_usage = g.physical[static_cast<size_t>(r.physical)].buffer_usage;
  }
}

// Transient allocations whose lives in a frame do not overlap take turns in one block of
// memory, whatever their descriptions: each joins the free block it fits best (the least
// growth, then the least waste). Buffers and images may alias too: at one offset and never
// alive together, the buffer-image granularity does not apply, and the executor keeps apart
// members whose memory types do not intersect on the device.
void plan_memory_blocks(CompiledGraph& g, bool alias_transients) {
  g.memory_blocks.clear();
  struct Life {
    int first = 0, last = -1;
    bool aliasable = false;
  };
  std::vector<Life> lives(g.physical.size());
  std::vector<size_t> order;
  for (size_t p = 0; p < g.physical.size(); ++p) {
    Life& life = lives[p];
    life.aliasable = alias_transients && !g.physical[p].carries_contents;
    life.first = INT32_MAX;
    for (int r : g.physical[p].resources) {
      const CompiledResource& res = g.resources[static_cast<size_t>(r)];
      life.aliasable = life.aliasable && !res.is_output && !res.carries_contents;
      life.first = std::min(life.first, res.first_pass);
      life.last = std::max(life.last, res.last_pass);
    }
    if (life.aliasable) order.push_back(p);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return lives[a].first < lives[b].first; });
  std::vector<MemoryBlock> blocks;
  std::vector<int> busy_until;
  for (size_t p : order) {
    const PhysicalResource& phys = g.physical[p];
    int best = -1;
    uint64_t best_growth = 0, best_waste = 0;
    for (size_t b = 0; b < blocks.size(); ++b) {
      if (busy_until[b] >= lives[p].first) continue;
      const uint64_t growth = phys.bytes > blocks[b].bytes ? phys.bytes - blocks[b].bytes : 0;
      const uint64_t waste = blocks[b].bytes > phys.bytes ? blocks[b].bytes - phys.bytes : 0;
      if (best < 0 || growth < best_growth || (growth == best_growth && waste < best_waste)) {
        best = static_cast<int>(b);
        best_growth = growth;
        best_waste = waste;
      }
    }
    if (best < 0) {
      blocks.emplace_back();
      busy_until.push_back(-1);
      best = static_cast<int>(blocks.size() - 1);
    }
    MemoryBlock& block = blocks[static_cast<size_t>(best)];
    block.physical.push_back(static_cast<int>(p));
    block.bytes = std::max(block.bytes, phys.bytes);
    busy_until[static_cast<size_t>(best)] = lives[p].last;
  }
  // A block of one is an allocation of its own.
  for (PhysicalResource& phys : g.physical) phys.memory_block = -1;
  for (MemoryBlock& block : blocks) {
    if (block.physical.size() < 2) continue;
    for (int p : block.physical) {
      g.physical[static_cast<size_t>(p)].memory_block = static_cast<int>(g.memory_blocks.size());
    }
    g.memory_blocks.push_back(std::move(block));
  }
  g.total_bytes = 0;
  g.total_bytes_unshared = 0;
  for (const PhysicalResource& phys : g.physical) {
    if (phys.memory_block < 0) g.total_bytes += phys.bytes;
  }
  for (const MemoryBlock& block : g.memory_blocks) g.total_bytes += block.bytes;
  for (const CompiledResource& r : g.resources) {
    if (r.physical >= 0) g.total_bytes_unshared += r.bytes;
  }
}

uint32_t mip_count(const ResourceInfo& info) {
  return info.kind == ResourceKind::Buffer ? 1 : info.mip_levels;
}

void apply_full_barriers(std::vector<Barrier>& barriers) {
  constexpr VkAccessFlags2 kAll = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  std::vector<Barrier> list;
  Barrier global;
  global.is_global = true;
  global.src_stages = global.dst_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  global.src_access = global.dst_access = kAll;
  list.push_back(global);
  for (Barrier b : barriers) {
    if (b.is_buffer || b.old_layout == b.new_layout) continue;  // the global one covers it
    b.src_stages = b.dst_stages = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    b.src_access = b.dst_access = kAll;
    list.push_back(b);
  }
  barriers = std::move(list);
}

}  // namespace

bool same_description(const ResourceInfo& a, const ResourceInfo& b) {
  return a.kind == b.kind && a.format == b.format && a.extent.width == b.extent.width &&
         a.extent.height == b.extent.height && a.extent.depth == b.extent.depth &&
         a.mip_levels == b.mip_levels && a.array_layers == b.array_layers &&
         a.clipmap_levels == b.clipmap_levels && a.buffer_size == b.buffer_size;
}

size_t barrier_count(const FrameBarriers& frame) {
  size_t count = frame.frame_start.size() + frame.history.size() + frame.frame_end.size();
  for (const std::vector<Barrier>& pass : frame.passes) count += pass.size();
  return count;
}

FrameSync::FrameSync(const CompiledGraph& graph) : graph_(&graph) {
  tracks_.resize(graph.physical.size());
  last_use_.resize(graph.physical.size());
  for (size_t p = 0; p < graph.physical.size(); ++p) {
    tracks_[p].resize(mip_count(graph.physical[p].info));
    last_use_[p].resize(tracks_[p].size());
  }
  block_owner_.assign(graph.memory_blocks.size(), -1);
  block_use_.assign(graph.memory_blocks.size(), SyncTrack{});
  // The first frame starts from nothing and finds where each resource ends a frame; the second
  // starts from there, as every frame after the first does.
  const std::vector<bool> none(graph.passes.size(), false);
  plan(none);
  end_use_ = last_use_;
  all_passes_frame_ = plan(none);
}

ResourceState FrameSync::state(size_t physical, uint32_t mip) const {
  const SyncTrack& t = tracks_.at(physical).at(mip);
  return ResourceState{t.layout, t.write_stages | t.read_stages, t.write_access};
}

FrameBarriers FrameSync::plan(const std::vector<bool>& skipped) {
  const CompiledGraph& g = *graph_;
  FrameBarriers frame;
  frame.passes.resize(g.passes.size());
  std::vector<std::vector<bool>> touched(g.resources.size());
  for (size_t r = 0; r < g.resources.size(); ++r) {
    touched[r].assign(mip_count(g.resources[r].info), false);
  }
  // Moves one mip of a resource to what `need` asks; returns the barrier it takes, if any.
  auto move = [&](int r, uint32_t m, const Need& need, bool discard) -> std::optional<Barrier> {
    const CompiledResource& res = g.resources[static_cast<size_t>(r)];
    const size_t p = static_cast<size_t>(res.physical);
    last_use_[p][m] = need.state;
    const int block = g.physical[p].memory_block;
    if (block >= 0 && block_owner_[static_cast<size_t>(block)] != static_cast<int>(p)) {
      // Moving into aliased memory: every first barrier of this allocation waits for what the
      // previous one did there.
      SyncTrack& before = block_use_[static_cast<size_t>(block)];
      if (block_owner_[static_cast<size_t>(block)] >= 0) {
        for (SyncTrack& t : tracks_[p]) {
          t.write_stages |= before.write_stages;
          t.write_access |= before.write_access;
          t.read_stages |= before.read_stages;
        }
      }
      block_owner_[static_cast<size_t>(block)] = static_cast<int>(p);
      before = SyncTrack{};
    }
    std::optional<Barrier> b =
        transition(tracks_[p][m], need, discard, res.info.kind == ResourceKind::Buffer);
    if (block >= 0) {
      SyncTrack& use = block_use_[static_cast<size_t>(block)];
      use.write_stages |= tracks_[p][m].write_stages;
      use.write_access |= tracks_[p][m].write_access;
      use.read_stages |= tracks_[p][m].read_stages;
    }
    if (b) {
      b->resource = r;
      b->base_mip = m;
      b->mip_count = 1;
    }
    return b;
  };
  for (size_t s = 0; s < g.passes.size(); ++s) {
    if (skipped[s]) continue;
    // Merge what this pass needs per (resource, mip).
    std::map<std::pair<int, uint32_t>, Need> needs;
    for (const SlotBinding& b : g.passes[s].bindings) {
      if (b.resource < 0) continue;
      const ResourceInfo& info = g.resources[static_cast<size_t>(b.resource)].info;
      const uint32_t first = b.info.mip < 0 ? 0 : static_cast<uint32_t>(b.info.mip);
      const uint32_t last = b.info.mip < 0 ? mip_count(info) : first + 1;
      for (uint32_t m = first; m < last; ++m) {
        Need& n = needs[{b.resource, m}];
        n.state.layout = b.state.layout;
        n.state.stages |= b.state.stages;
        n.state.access |= b.state.access;
        n.reads = n.reads || b.is_input || b.spec->access == Access::StorageReadWrite;
        n.writes = n.writes || (!b.is_input && access_writes(b.spec->access));
      }
    }
    for (const auto& [key, need] : needs) {
      const auto [r, m] = key;
      const CompiledResource& res = g.resources[static_cast<size_t>(r)];
      const bool first_use = !touched[static_cast<size_t>(r)][m];
      touched[static_cast<size_t>(r)][m] = true;
      const std::optional<Barrier> b = move(r, m, need, first_use && !res.carries_contents);
      // A carried resource's first transition can happen as the frame starts.
      if (b)
        append_merged(first_use && res.carries_contents ? frame.frame_start : frame.passes[s], *b);
    }
    if (g.full_barriers) apply_full_barriers(frame.passes[s]);
  }
  // The previous-frame copies: the current version is read, its copy overwritten whole.
  for (const HistoryCopy& copy : g.history_copies) {
    const ResourceInfo& info = g.resources[static_cast<size_t>(copy.from)].info;
    Need read;
    read.state = state_for(Access::TransferRead, kStageTransfer, info.kind, info.format);
    read.reads = true;
    Need write;
    write.state = state_for(Access::TransferWrite, kStageTransfer, info.kind, info.format);
    write.writes = true;
    for (uint32_t m = 0; m < mip_count(info); ++m) {
      if (const std::optional<Barrier> b = move(copy.from, m, read, false))
        append_merged(frame.history, *b);
      if (const std::optional<Barrier> b = move(copy.to, m, write, true))
        append_merged(frame.history, *b);
    }
  }
  for (const auto& [name, r] : g.outputs) {
    const CompiledResource& res = g.resources[static_cast<size_t>(r)];
    if (res.physical < 0) continue;
    const bool is_buffer = res.info.kind == ResourceKind::Buffer;
    Need need;
    need.state = state_for(Access::TransferRead, kStageTransfer, res.info.kind, res.info.format);
    need.reads = true;
    for (uint32_t m = 0; m < mip_count(res.info); ++m) {
      const SyncTrack& t = tracks_[static_cast<size_t>(res.physical)][m];
      // Outputs named twice are transitioned once.
      if (!is_buffer && t.layout == need.state.layout && covered(t, need.state)) continue;
      if (const std::optional<Barrier> b = move(r, m, need, false))
        append_merged(frame.frame_end, *b);
    }
  }
  // Images a skipped pass left in another layout go back to where every frame ends.
  for (size_t p = 0; p < end_use_.size(); ++p) {
    const PhysicalResource& phys = g.physical[p];
    if (phys.info.kind == ResourceKind::Buffer) continue;
    for (uint32_t m = 0; m < end_use_[p].size(); ++m) {
      const ResourceState& end = end_use_[p][m];
      if (end.layout == VK_IMAGE_LAYOUT_UNDEFINED || tracks_[p][m].layout == end.layout) continue;
      Need need;
      need.state = end;
      need.reads = true;
      if (const std::optional<Barrier> b = move(phys.resources.back(), m, need, false)) {
        append_merged(frame.frame_end, *b);
      }
    }
  }
  return frame;
}

void plan_resources(CompiledGraph& g, const CompileOptions& options) {
  plan_lifetimes_and_usage(g);
  plan_physical(g, options.alias_transients);
  plan_memory_blocks(g, options.alias_transients);
  const FrameSync sync(g);
  const FrameBarriers& frame = sync.all_passes_frame();
  g.frame_start = frame.frame_start;
  g.frame_end = frame.frame_end;
  g.history_barriers = frame.history;
  for (size_t s = 0; s < g.passes.size(); ++s) g.passes[s].barriers = frame.passes[s];
  for (CompiledResource& r : g.resources) {
    if (r.physical < 0) continue;
    r.end_state.clear();
    for (uint32_t m = 0; m < mip_count(r.info); ++m) {
      r.end_state.push_back(sync.state(static_cast<size_t>(r.physical), m));
    }
  }
}

}  // namespace voxgi::graph
