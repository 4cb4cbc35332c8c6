// What every technique's insertion entry shares on the GPU: the outcome
// tallies (SPEC invariant 1), striped so the fragments of a frame do not all
// hit the same few addresses, and the capture mode, which appends every
// incoming fragment so the CPU path can replay exactly what the rasterizer
// produced.
struct HaFragment {
  uint x;
  uint y;
  float depth;  // as given: the CPU path derives the same depth code from it
  uint rgba;
  uint coverage;  // as given (0: the whole pixel); the CPU path derives the same mask from it
};

layout(std430, binding = HABUFFER_BINDING_COUNTERS) buffer HaCounters { uint ha_counters[]; };
layout(std430, binding = HABUFFER_BINDING_CAPTURE) buffer HaCapture {
  uint ha_capture_count;  // may exceed the capacity: the host sees the overflow and gathers again
  uint ha_capture_pad0;
  uint ha_capture_pad1;
  uint ha_capture_pad2;
  HaFragment ha_captured[];
};

void ha_capture(uvec2 pixel, float depth, uint coverage, uint rgba) {
  uint i = atomicAdd(ha_capture_count, 1u);
  if (i < habuffer_capture_capacity) ha_captured[i] = HaFragment(pixel.x, pixel.y, depth, rgba, coverage);
}

// The counter stripe of a call: neighbouring pixels (the lanes of one SIMD
// group) add to different cache lines; the host sums the stripes.
uint ha_counter_stripe(uvec2 p) { return (p.x + p.y * 5u) & (HABUFFER_COUNTER_STRIPES - 1u); }

// Adds n to counter `counter` (an outcome or HABUFFER_COUNTER_*) in the stripe of `pixel`.
void ha_counter_add(uvec2 pixel, uint counter, uint n) {
  atomicAdd(ha_counters[ha_counter_stripe(pixel) * HABUFFER_COUNTER_STRIDE + counter], n);
}
