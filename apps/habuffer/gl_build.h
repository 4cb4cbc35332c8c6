/// @file
/// The GPU path of the commands that build from a stream (build-lists, demo):
/// a headless context, one frame of compute insertion (lossless mode
/// regathers on the GPU), and the read-back imported into a CPU-side buffer
/// so lists, dumps and stats are written the same way as the CPU path's.
/// Private to the CLI.
#pragma once

#include <span>

#include "habuffer/fragment.h"
#include "hash_options.h"
#include "report_json.h"

namespace habuffer::cli {

/// Any technique of `options` on the GPU. Sets timing.build_ms to the
/// insertion alone (upload, every gather, resume rounds, sort pass,
/// counters), without the context's creation and the shader compilation, and
/// the GL fields of `timing`. Throws DataError when no usable OpenGL or no
/// mode for the layout is found.
TechniqueBuild build_on_gl(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing);

/// The HA-buffer's build on the GPU (options.technique must be ha).
BuildResult build_ha_on_gl(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing);

}  // namespace habuffer::cli
