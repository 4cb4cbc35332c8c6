#include "habuffer/vk/frame_buffers.h"

#include <algorithm>

#include "habuffer/gl/module_variant.h"
#include "habuffer/gpu_tally.h"
#include "habuffer/shared/ha_constants.h"
#include "habuffer/vk/vulkan_error.h"
#include "habuffer/vk/vulkan_glsl.h"

namespace habuffer::vk {

std::string frame_variant_defines(AtomicMode mode, const VulkanInfo& info) {
  gl::ModuleVariant v;
  v.slot_read_first = mode == AtomicMode::Emulated64;
  v.max_age_read_first = info.software;
  return vulkan_device_defines(info.lavapipe) + v.defines();
}

std::vector<BoundBuffer> frame_bindings(const VulkanTechnique& t, const FrameBuffers& frame) {
  const gl::GlBindings b = vulkan_bindings();
  std::vector<BoundBuffer> out = t.buffers();
  for (unsigned point = 1; point <= ComputePipeline::kStorageBindings; ++point)
    if (std::none_of(out.begin(), out.end(), [&](const BoundBuffer& x) { return x.binding == point; }) &&
        point != b.counters && point != b.capture && point != b.stream && point != b.deferred)
      out.push_back({point, frame.capture});
  out.push_back({b.params, frame.params});
  out.push_back({b.counters, frame.counters});
  out.push_back({b.capture, frame.capture});
  out.push_back({b.stream, frame.stream});
  out.push_back({b.deferred, frame.deferred});
  return out;
}

ParamBlock frame_params(const VulkanTechnique& t, std::uint32_t phase) {
  ParamBlock p;
  p.habuffer_gather_phase = phase;
  p.habuffer_lock_spin_limit = HABUFFER_DEFAULT_LOCK_SPIN_LIMIT;
  p.habuffer_screen_size[0] = t.config().buffer.screen.x;
  p.habuffer_screen_size[1] = t.config().buffer.screen.y;
  t.write_params(p);
  return p;
}

Counters counters_from_words(std::span<const std::uint32_t> words) {
  if (words.size() < HABUFFER_COUNTER_WORDS)
    throw VulkanError("a gather's counters need " + std::to_string(HABUFFER_COUNTER_WORDS) + " words, " +
                      std::to_string(words.size()) + " given");
  if (const std::uint32_t foreign = words[HABUFFER_COUNTER_FOREIGN]; foreign > 0)
    throw VulkanError(std::to_string(foreign) + " insert calls came from another module than the frame's");
  const auto tally = stripe_tally(words.first(HABUFFER_COUNTER_WORDS));
  Counters c;
  c.add_tally(tally.data());
  c.merge_duplicates(tally[HABUFFER_COUNTER_MERGED]);
  return c;
}

}  // namespace habuffer::vk
