/// @file
/// Compile-time variants of the GLSL insertion module. Each is a #define in
/// the module's text, so work a frame did not ask for is not compiled into
/// its shaders at all (a branch on a uniform would still cost its test and
/// registers per fragment). The frame driver writes them into
/// GlFrameDriver::module_source() and into its own passes: compile every
/// shader that calls ha_insert from that text.
#pragma once

#include <string>

namespace habuffer::gl {

struct ModuleVariant {
  /// Tally slot writes (FrameReport::slot_writes): a register count per slot
  /// raise and one more atomic add per HA-buffer insert call.
  bool count_writes = false;
  /// Before a slot's atomicMax, one plain load that skips the atomic when
  /// the slot already holds a larger record (SPEC 6's step with the same
  /// outcome). Saves emulated64 a lock per such probe; on native atomics it
  /// is one more dependent load per probe.
  bool slot_read_first = true;
  /// Read the max-age cell before raising it, skipping the atomicMax when
  /// the cell is already high enough. Off: one atomicMax whose result is
  /// unused (a fire-and-forget reduction on NVIDIA hardware).
  bool max_age_read_first = false;

  /// The #define lines of this variant (HABUFFER_COUNT_WRITES,
  /// HABUFFER_SLOT_READ_FIRST, HABUFFER_MAX_AGE_READ_FIRST), to precede the module.
  [[nodiscard]] std::string defines() const;
  /// "count_writes=0 slot_read_first=1 max_age_read_first=0": for reports and benchmark labels.
  [[nodiscard]] std::string str() const;

  bool operator==(const ModuleVariant&) const = default;
};

}  // namespace habuffer::gl
