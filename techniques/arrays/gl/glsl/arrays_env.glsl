// Fixed arrays' environment on the GPU (techniques/arrays/cpu/include/habuffer/techniques/arrays/arrays.glsl): the
// per-pixel counters and the layers; the largest overflow goes to one word
// of the counters buffer.
layout(std430, binding = HABUFFER_BINDING_COUNTS) buffer HaCounts { uint ha_counts[]; };
layout(std430, binding = HABUFFER_BINDING_LAYERS) buffer HaLayers { uvec2 ha_layer_entries[]; };

uint fa_count_add(uint pixel) { return atomicAdd(ha_counts[pixel], 1u); }
uint fa_load_count(uint pixel) { return ha_counts[pixel]; }
void fa_store_count(uint pixel, uint n) { ha_counts[pixel] = n; }
uvec2 fa_load_layer(uint slot) { return ha_layer_entries[slot]; }
void fa_store_layer(uint slot, uvec2 e) { ha_layer_entries[slot] = e; }
void fa_note_overflow(uint arrived) { atomicMax(ha_counters[HABUFFER_COUNTER_MOST_ARRIVED], arrived); }
