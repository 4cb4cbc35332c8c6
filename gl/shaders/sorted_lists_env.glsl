// Sorted lists' environment on the GPU (core/shared/ha_lists.glsl and
// ha_sorted_lists.glsl): the lists' buffers, coherent, because an insertion
// reads the links and entries other invocations wrote in the same gather;
// a node's entry and link are written, then a buffer barrier, then the
// compare-and-swap that links it, so whoever reads the link reads them too.
layout(std430, binding = HA_BINDING_HEADS) coherent buffer HaHeads { uint ha_heads[]; };
layout(std430, binding = HA_BINDING_NODES) coherent buffer HaNodes { uvec2 ha_nodes[]; };
layout(std430, binding = HA_BINDING_LINKS) coherent buffer HaLinks { uint ha_links[]; };

uint ll_allocate_node() { return atomicAdd(ha_counters[HA_COUNTER_NODES], 1u); }
uint ll_exchange_head(uint pixel, uint link) { return atomicExchange(ha_heads[pixel], link); }
uint ll_load_head(uint pixel) { return ha_heads[pixel]; }
void ll_store_head(uint pixel, uint link) { ha_heads[pixel] = link; }
uvec2 ll_load_entry(uint node) { return ha_nodes[node]; }
void ll_store_entry(uint node, uvec2 e) { ha_nodes[node] = e; }
uint ll_load_next(uint node) { return ha_links[node]; }
void ll_store_next(uint node, uint link) { ha_links[node] = link; }

uint sl_load_link(uint pixel, uint where) { return where == 0u ? ha_heads[pixel] : ha_links[where - 1u]; }
uint sl_swap_link(uint pixel, uint where, uint expected, uint link) {
  memoryBarrierBuffer();
  if (where == 0u) return atomicCompSwap(ha_heads[pixel], expected, link);
  return atomicCompSwap(ha_links[where - 1u], expected, link);
}
