// Saturation depth's environment on the GPU (core/record/include/habuffer/shared/ha_saturation.glsl):
// one code per pixel, raised by atomicMax; stale reads reject less, never wrongly.
layout(std430, binding = HABUFFER_BINDING_SATURATION) buffer HaSaturationCodes { uint ha_saturation_codes[]; };

uint ha_load_saturation(uint pixel) { return ha_saturation_codes[pixel]; }
void ha_max_saturation(uint pixel, uint code) { atomicMax(ha_saturation_codes[pixel], code); }
