// The GLSL spellings of what the shared sources of core/include/habuffer/shared/ expect from
// their host (the C++ side is core/include/habuffer/glsl_env.h).
#define ha_index uint
#define HABUFFER_INOUT(T) inout T
#define ha_floor floor
#define ha_float_bits floatBitsToUint
