/// @file
/// The GPU paths' read-back of node lists (heads, node entries, links, the
/// nodes asked for) into the CPU container of the same technique: one
/// function for the OpenGL and the Vulkan parts of lists, sorted-lists and
/// paged-lists.
#pragma once

#include <cstdint>
#include <memory>
#include <span>

#include <glm/vec2.hpp>

#include "habuffer/fragment_buffer.h"
#include "habuffer/technique.h"

namespace habuffer {

/// A CPU container `Lists` with import_state (LinkedLists, PagedLists)
/// holding what a device's node lists held; throws as its import_state does.
template <class Lists>
std::unique_ptr<FragmentBuffer> import_node_lists(const TechniqueConfig& config, std::span<const std::uint32_t> heads,
                                                  std::span<const glm::uvec2> entries,
                                                  std::span<const std::uint32_t> links, std::uint64_t requested) {
  auto lists = std::make_unique<Lists>(config);
  lists->import_state(heads, entries, links, requested);
  return lists;
}

}  // namespace habuffer
