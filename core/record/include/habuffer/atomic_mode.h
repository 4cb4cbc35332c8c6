/// @file
/// How a GPU path raises slots by atomicMax, and how each path (OpenGL,
/// Vulkan) chooses the mode from what its device offers: one rule for every
/// path, so a layout runs the same mode wherever the device allows it.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "habuffer/record_layout.h"

namespace habuffer {

/// How the GPU paths raise slots by atomicMax; it fixes the record layout.
enum class AtomicMode {
  Native32,    ///< L32 records, atomicMax on uint
  Native64,    ///< L64 records, atomicMax on uint64_t (GL_NV_shader_atomic_int64, Vulkan's shaderBufferInt64Atomics)
  Emulated64,  ///< L64 records on devices without 64-bit atomics (per-slot lock from 32-bit atomics)
};

/// "native32", "native64" or "emulated64".
std::string to_string(AtomicMode mode);

/// What a device offers the atomic modes, and how its path names what it
/// lacks (the words of the errors).
struct AtomicSupport {
  bool int64_types = false;   ///< 64-bit integers in shaders
  bool atomic_int64 = false;  ///< 64-bit atomics on storage buffers
  std::string api;            ///< "OpenGL", "Vulkan"
  std::string device;         ///< the renderer or device name
  std::string int64_name;     ///< the feature that gives 64-bit types (GL_ARB_gpu_shader_int64, shaderInt64)
  std::string atomic_name;    ///< the feature that gives 64-bit atomics
};

/// Modes a device can run, in order of preference.
std::vector<AtomicMode> runnable_atomic_modes(const AtomicSupport& support);

/// The mode named by the environment variable HABUFFER_ATOMIC_MODE (native32,
/// native64 or emulated64), for tests and benchmarks that compare modes on one
/// GPU (emulated64 forced on a GPU with 64-bit atomics); none when unset.
/// Throws std::invalid_argument naming the variable for any other value.
std::optional<AtomicMode> atomic_mode_override();

/// Emulated64's lock words for `slots` 64-bit slots: one per
/// 2^HABUFFER_LOCK_SHIFT (every GPU path's lock buffer).
std::uint64_t emulated64_lock_words(std::uint64_t slots);

/// The mode a path runs a layout in: the override when it holds the layout
/// (native32 for L32; native64 or emulated64 for L64); else L32 native32,
/// L64 native64 where the device has 64-bit atomics, else emulated64; none
/// without 64-bit types. Throws std::invalid_argument when the override
/// cannot run on the device or cannot hold the layout (native32 forced for
/// L64), naming the variable, the mode, the device and what it lacks; a
/// 64-bit mode forced beside L32 (whose one mode is native32) is said to
/// `warn` (each path passes its once-per-process log), never replaced
/// silently.
std::optional<AtomicMode> chosen_atomic_mode(const AtomicSupport& support, Layout layout,
                                             const std::function<void(const std::string&)>& warn);

}  // namespace habuffer
