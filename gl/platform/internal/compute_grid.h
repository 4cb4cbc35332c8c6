// One invocation per item on a 2D grid of work groups (a 1D grid stops at
// 65535 groups), for the compute passes whose shaders compute their item as
// (group.y * groups.x + group.x) * local_size + local index.
#pragma once

#include <epoxy/gl.h>

#include <algorithm>
#include <cstdint>

namespace habuffer::gl {

inline void dispatch_grid(std::uint64_t items, std::uint64_t local_size) {
  const std::uint64_t groups = std::max<std::uint64_t>((items + local_size - 1) / local_size, 1);
  const auto gx = static_cast<GLuint>(std::min<std::uint64_t>(groups, 65535));
  const auto gy = static_cast<GLuint>((groups + gx - 1) / gx);
  glDispatchCompute(gx, gy, 1);
}

}  // namespace habuffer::gl
