/// @file
/// What a build attempt asked for, the count lossless mode's next size is
/// computed from (TechniqueConfig::grown): one rule for the CPU's
/// TechniqueFrames and the Vulkan build.
#pragma once

#include "habuffer/counters.h"
#include "habuffer/fragment_buffer.h"
#include "habuffer/technique.h"

namespace habuffer {

/// What an attempt into `buffer` asked for: the container's own need (the
/// nodes a pool technique asked for, the most fragments a pixel received),
/// and the records it asked to keep (every fragment it received has an
/// outcome: Counters::records_needed).
GrowthNeed attempt_need(const FragmentBuffer& buffer, const Counters& counters);

}  // namespace habuffer
