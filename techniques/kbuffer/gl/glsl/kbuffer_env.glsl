// The k-buffer's environment on the GPU (techniques/kbuffer/cpu/include/habuffer/techniques/kbuffer/kbuffer.glsl): its
// layers are the mode's slot table at the k-buffer's own point (the prelude
// declares it at HABUFFER_RECORDS_BINDING, and the lock words of
// emulated64), then its occupancy map and per-pixel limits.
uint ha_call_writes = 0u;
#define HABUFFER_RECORDS_BINDING HABUFFER_BINDING_SLOTS

layout(std430, binding = HABUFFER_BINDING_OCCUPANCY) buffer KbOccupancy { uint kb_occupancy[]; };
layout(std430, binding = HABUFFER_BINDING_LIMITS) buffer KbLimits { uint kb_limits[]; };

void kb_or_occupancy(uint word, uint bits) {
  if ((kb_occupancy[word] & bits) != bits) atomicOr(kb_occupancy[word], bits);
}
uint kb_load_occupancy(uint word) { return kb_occupancy[word]; }
uint kb_load_limit(uint pixel) { return kb_limits[pixel]; }
void kb_store_limit(uint pixel, uint bucket) { kb_limits[pixel] = bucket; }
uint ha_lowest_bit(uint w) { return uint(findLSB(w)); }
