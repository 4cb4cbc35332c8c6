/// @file
/// A fragment stream built on the GPU path: one frame of compute insertion
/// (lossless mode regathers on the GPU) into any technique, read back into
/// its CPU container, so lists, dumps and stats come out as the CPU path's.
/// The CLI's build-lists and demo and the Python module call it.
#pragma once

#include <cstdint>
#include <span>
#include <string>

#include "habuffer/fragment.h"
#include "habuffer/lossless_build.h"
#include "habuffer/resize_policy.h"
#include "habuffer/technique.h"

namespace habuffer {

/// What a GPU build reports besides the TechniqueBuild.
struct GlBuildInfo {
  double build_ms = 0.0;  ///< the insertion alone: upload, gathers, resume rounds, sort pass, counters
  std::string atomic_mode;  ///< the mode that ran ("native64", "emulated64", "native32")
  std::string renderer;     ///< GL_RENDERER
  std::uint64_t deferred = 0;             ///< insert calls cut short and resumed (summed over rounds)
  std::uint32_t resume_rounds = 0;        ///< passes that resumed deferred calls
  std::uint32_t cut_short_retries = 0;    ///< gathers retried because calls were cut short
};

/// `fragments` into `config`'s technique on the GPU of the current GL
/// context, lossless mode by `policy` and `max_attempts` as build_technique,
/// by its rule (lossless_attempts: no growth where growing cannot help, then
/// TechniqueBuild::too_deep), so both paths make the same attempts; a lossy
/// result is returned as it is (require_lossless). A pool of 0 is the
/// library's automatic pool. Throws GlError when the
/// context has no mode for the layout, std::invalid_argument for a bad
/// configuration, std::out_of_range for a fragment off the screen.
TechniqueBuild build_technique_on_gl(const TechniqueConfig& config, const OffsetSource& offsets,
                                     std::span<const Fragment> fragments, const ResizePolicy& policy,
                                     std::uint32_t max_attempts, GlBuildInfo* info = nullptr);

}  // namespace habuffer
