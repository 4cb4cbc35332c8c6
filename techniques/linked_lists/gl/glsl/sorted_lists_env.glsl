// Sorted lists' part of the environment on the GPU (techniques/linked_lists/cpu/include/habuffer/techniques/linked_lists/sorted_lists.glsl),
// after lists_env.glsl, whose buffers the module assembly makes coherent
// (HABUFFER_LISTS_QUALIFIER): an insertion reads the links and entries other
// invocations wrote in the same gather. A node's entry and link are
// written, then a buffer barrier, then the compare-and-swap that links it,
// so whoever reads the link reads them too.
// The fence between writes and the atomic that publishes them. A module
// assembly may define it first: the Vulkan path defines it empty on
// lavapipe (vk::vulkan_device_defines says why).
#ifndef HABUFFER_BUFFER_FENCE
#define HABUFFER_BUFFER_FENCE() memoryBarrierBuffer()
#endif
uint sl_load_link(uint pixel, uint where) { return where == 0u ? ha_heads[pixel] : ha_links[where - 1u]; }
uint sl_swap_link(uint pixel, uint where, uint expected, uint link) {
  HABUFFER_BUFFER_FENCE();
  if (where == 0u) return atomicCompSwap(ha_heads[pixel], expected, link);
  return atomicCompSwap(ha_links[where - 1u], expected, link);
}
