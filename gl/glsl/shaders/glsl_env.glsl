// The GLSL spellings of what the shared sources of core/{record,hash}/include/habuffer/shared/ expect from
// their host (the C++ side is core/record/include/habuffer/glsl_env.h).
#define ha_index uint
#define HABUFFER_INOUT(T) inout T
// No fused multiply-add where a result must equal the CPU path's: the C++
// side compiles with -ffp-contract=off, and the NVIDIA compiler fuses
// (the H100 gave images one rounding apart without it).
#define HABUFFER_PRECISE precise
#define HABUFFER_UNUSED(x)
#define ha_floor floor
#define ha_float_bits floatBitsToUint
