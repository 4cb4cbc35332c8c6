// A build without the Vulkan path (HABUFFER_WITH_VULKAN off or its
// packages absent): RenderPath::Vk is refused in one line.
#include <stdexcept>

#include "frame_builder.h"
#include "frame_path.h"

namespace habuffer {

bool runs_on_path(RenderPath path, Technique) { return path != RenderPath::Vk; }

void check_runs_on_path(RenderPath path, Technique) {
  if (path == RenderPath::Vk)
    throw std::invalid_argument("this habuffer was built without the Vulkan path (HABUFFER_WITH_VULKAN): use gl or cpu");
}

std::unique_ptr<FrameBuilder> make_vulkan_frame_builder(const RenderSettings&) {
  throw std::invalid_argument("this habuffer was built without the Vulkan path (HABUFFER_WITH_VULKAN): render on gl or cpu");
}

}  // namespace habuffer
