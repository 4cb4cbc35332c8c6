/// @file
/// The Vulkan path of build-lists: a headless device, the stream built
/// through the shared compute entry (lossless mode regathers there), and the
/// read-back in the CPU's container, so lists, dumps and stats are written
/// as the CPU path's. Private to the CLI; compiled where habuffer::vk is.
#pragma once

#include <span>

#include "habuffer/fragment.h"
#include "habuffer/lossless_build.h"
#include "hash_options.h"
#include "report_json.h"

namespace habuffer::cli {

/// The technique of `options` on Vulkan. Sets timing.build_ms (the upload
/// and every attempt's gather with its counters, as the GL path's; not the
/// device, the compilation or the read-back) and the vk fields of `timing`. Throws
/// DataError when no usable Vulkan device, technique or mode is found.
TechniqueBuild build_on_vk(const HashOptions& options, std::span<const Fragment> fragments, BuildTiming& timing);

}  // namespace habuffer::cli
