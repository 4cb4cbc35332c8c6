// Linked lists' environment on the GPU (techniques/linked_lists/cpu/include/habuffer/techniques/linked_lists/lists.glsl): the head
// image, the node pool's entries and links, and the node counter (one word of
// the counters buffer, zeroed with the tallies before every gather). No
// invocation of lists sorted after the gather reads another's plain stores
// within a pass (the sort and resolve passes follow a barrier), so their
// buffers need not be coherent; sorted lists define HABUFFER_LISTS_QUALIFIER as
// coherent (sorted_lists_env.glsl says why).
#ifndef HABUFFER_LISTS_QUALIFIER
#define HABUFFER_LISTS_QUALIFIER
#endif
layout(std430, binding = HABUFFER_BINDING_HEADS) HABUFFER_LISTS_QUALIFIER buffer HaHeads { uint ha_heads[]; };
layout(std430, binding = HABUFFER_BINDING_NODES) HABUFFER_LISTS_QUALIFIER buffer HaNodes { uvec2 ha_nodes[]; };
layout(std430, binding = HABUFFER_BINDING_LINKS) HABUFFER_LISTS_QUALIFIER buffer HaLinks { uint ha_links[]; };

uint ll_allocate_node() { return atomicAdd(ha_counters[HABUFFER_COUNTER_NODES], 1u); }
uint ll_exchange_head(uint pixel, uint link) { return atomicExchange(ha_heads[pixel], link); }
uint ll_load_head(uint pixel) { return ha_heads[pixel]; }
void ll_store_head(uint pixel, uint link) { ha_heads[pixel] = link; }
uvec2 ll_load_entry(uint node) { return ha_nodes[node]; }
void ll_store_entry(uint node, uvec2 e) { ha_nodes[node] = e; }
uint ll_load_next(uint node) { return ha_links[node]; }
void ll_store_next(uint node, uint link) { ha_links[node] = link; }
