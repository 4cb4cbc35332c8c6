/// @file
/// Losses said out loud: any run whose fragments did not all end stored or
/// merged as duplicates prints one warning line on stderr with the counts,
/// whether or not a stats file was asked for (SPEC invariant 1).
#pragma once

#include <cstdint>
#include <string>

#include "habuffer/fragment.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::cli {

// lost_fragments and loss_summary are the library's (habuffer/counters.h).

/// What keeps a technique's dropped fragments (its descriptor's hint).
inline std::string lossless_hint(Technique t) { return loss_hint(t); }

/// Prints "WHO: warning: SUMMARY[CONTEXT][; HINT]" when anything was lost
/// (WHO: "habuffer render", "habuffer-view"); the hint only when fragments
/// failed (not culled or invalid).
void warn_losses(const std::string& who, const Counters& c, const std::string& context, const std::string& hint);

/// Prints "WHO: lossless mode: SUMMARYCONTEXT", the one line of a
/// --lossless run that still lost fragments (it exits 1).
void report_lossless_failure(const std::string& who, const Counters& c, const std::string& context);

/// Why a lossless run of GL frames still lost fragments, for the end of that
/// line: the pixel deeper than AMAX (`too_deep`: too_deep_message, or empty),
/// the context's limits, a single attempt, or a hint at the age bits.
std::string lossless_failure_reason(const std::string& too_deep, bool growth_limited, std::uint32_t max_attempts,
                                    Technique t);

}  // namespace habuffer::cli
