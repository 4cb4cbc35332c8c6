/// @file
/// The C++ side of the shared GLSL sources in core/{record,hash}/include/habuffer/shared/: the types and
/// builtins a .glsl file expects, provided at class scope so that a class
/// template can #include a shared file and turn its functions into members.
#pragma once

#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "habuffer/shared/ha_constants.h"

/// GLSL's inout parameters are C++ references.
#define HABUFFER_INOUT(T) T&
/// GLSL's `precise` (no fused multiply-add): the C++ side is compiled with
/// -ffp-contract=off, so nothing to say here.
#define HABUFFER_PRECISE
/// A parameter one build of a shared function does not read (GLSL: nothing).
#define HABUFFER_UNUSED(x) (void)(x)

/// GLSL's types (uint, uvec2, vec3, vec4) and the builtins the shared sources
/// call (ha_floor, ha_float_bits, min, max), declared at class scope.
#define HABUFFER_GLSL_CLASS_PRELUDE                                              \
  using uint = std::uint32_t;                                              \
  using uvec2 = glm::uvec2;                                                \
  using vec3 = glm::vec3;                                                  \
  using vec4 = glm::vec4;                                                  \
  static float ha_floor(float x) { return std::floor(x); }                 \
  static uint ha_float_bits(float x) { return std::bit_cast<uint>(x); }   \
  static uint min(uint a, uint b) { return a < b ? a : b; }                \
  static float min(float a, float b) { return a < b ? a : b; }             \
  static float max(float a, float b) { return a > b ? a : b; }

/// The private array of HABUFFER_SORT_LOCAL entries that ha_entries.glsl sorts in
/// (a GLSL shader's private array; here a member, so each kernel copy, one per
/// thread, has its own).
#define HABUFFER_GLSL_CLASS_LOCAL_ARRAY                                          \
  std::array<glm::uvec2, HABUFFER_SORT_LOCAL> ha_local_{};                       \
  glm::uvec2 ha_local_get(std::uint32_t k) const { return ha_local_[k]; }  \
  void ha_local_set(std::uint32_t k, glm::uvec2 e) { ha_local_[k] = e; }

namespace habuffer {

/// GLSL's atomicMax on the CPU, for every kernel's slots, cells and images:
/// returns the old value, leaves max(old, x). Each failed strong exchange saw
/// a strictly larger value, so the loop ends after at most as many rounds as
/// other threads raised this very word. Without Concurrent: plain loads and stores.
template <bool Concurrent, class T>
T ha_fetch_max(T& v, T x) {
  if constexpr (Concurrent) {
    std::atomic_ref<T> a(v);
    T cur = a.load(std::memory_order_relaxed);
    while (cur < x && !a.compare_exchange_strong(cur, x, std::memory_order_relaxed)) {
    }
    return cur;
  } else {
    const T cur = v;
    if (cur < x) v = x;
    return cur;
  }
}

/// A plain read of a word other threads may write (relaxed atomic when Concurrent).
template <bool Concurrent, class T>
T ha_fetch(const T& v) {
  if constexpr (Concurrent) return std::atomic_ref<T>(const_cast<T&>(v)).load(std::memory_order_relaxed);
  return v;
}

}  // namespace habuffer
