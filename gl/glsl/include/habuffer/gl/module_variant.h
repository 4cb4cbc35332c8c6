/// @file
/// Compile-time variants of the GLSL insertion module. Each is a #define in
/// the module's text, so work a frame did not ask for is not compiled into
/// its shaders at all (a branch on a uniform would still cost its test and
/// registers per fragment). The frame driver writes them into
/// GlFrameDriver::module_source() and into its own passes: compile every
/// shader that calls habuffer_insert from that text.
#pragma once

#include <optional>
#include <string>

#include "habuffer/gl/gl_info.h"

namespace habuffer::gl {

/// Every variant builds the same table and max-age table (SPEC 9); they
/// differ in speed only. An unset choice is the measured faster one for the
/// atomic mode and implementation (resolved(); docs/performance.md, "Issue
/// 26: GPU bookkeeping").
struct ModuleVariant {
  /// Tally slot writes (FrameReport::slot_writes): a register count per slot
  /// raise and one more atomic add per HA-buffer insert call.
  bool count_writes = false;
  /// Before a slot's atomicMax, one plain load that skips the atomic when
  /// the slot already holds a larger record (SPEC 6's step with the same
  /// outcome). Unset: on in emulated64 (the load saves a lock), off with
  /// native atomics (one dependent load more per probe; 7-10 % slower on
  /// llvmpipe in native32). The CPU path always reads first.
  std::optional<bool> slot_read_first;
  /// Read the max-age cell before raising it, skipping the atomicMax when
  /// the cell is already high enough. Unset: on for a software rasterizer
  /// (a locked read-modify-write on the CPU costs more than the load; 3-7 %
  /// on llvmpipe), off on a GPU: one atomicMax whose result is unused, a
  /// fire-and-forget reduction on NVIDIA hardware.
  std::optional<bool> max_age_read_first;

  /// Every choice made: unset ones by `mode` and `info` (see each).
  [[nodiscard]] ModuleVariant resolved(AtomicMode mode, const GlInfo& info) const;
  /// The #define lines of the choices made (HABUFFER_COUNT_WRITES,
  /// HABUFFER_SLOT_READ_FIRST, HABUFFER_MAX_AGE_READ_FIRST), to precede the
  /// module; an unset one is left to the module's own default (read-first
  /// slot loads, no max-age read), as in the installed GLSL files.
  [[nodiscard]] std::string defines() const;
  /// "count_writes=0 slot_read_first=1 max_age_read_first=auto": for reports and benchmark labels.
  [[nodiscard]] std::string str() const;

  bool operator==(const ModuleVariant&) const = default;
};

}  // namespace habuffer::gl
