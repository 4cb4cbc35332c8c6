// The C++ side of the shared GLSL sources in core/shared/: the types and
// builtins a .glsl file expects, provided at class scope so that a class
// template can #include a shared file and turn its functions into members.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/glm.hpp>

#include "../../shared/ha_constants.h"

// GLSL's inout parameters are C++ references.
#define HA_INOUT(T) T&

#define HA_GLSL_CLASS_PRELUDE                                              \
  using uint = std::uint32_t;                                              \
  using uvec2 = glm::uvec2;                                                \
  using vec3 = glm::vec3;                                                  \
  using vec4 = glm::vec4;                                                  \
  static float ha_floor(float x) { return std::floor(x); }                 \
  static uint ha_float_bits(float x) { return std::bit_cast<uint>(x); }   \
  static uint min(uint a, uint b) { return a < b ? a : b; }                \
  static float min(float a, float b) { return a < b ? a : b; }             \
  static float max(float a, float b) { return a > b ? a : b; }

// The private array of HA_SORT_LOCAL entries that ha_entries.glsl sorts in
// (a GLSL shader's private array; here a member, so each kernel copy, one per
// thread, has its own).
#define HA_GLSL_CLASS_LOCAL_ARRAY                                          \
  std::array<glm::uvec2, HA_SORT_LOCAL> ha_local_{};                       \
  glm::uvec2 ha_local_get(std::uint32_t k) const { return ha_local_[k]; }  \
  void ha_local_set(std::uint32_t k, glm::uvec2 e) { ha_local_[k] = e; }
