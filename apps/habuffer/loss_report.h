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

/// Prints "habuffer COMMAND: warning: SUMMARY[CONTEXT][; HINT]" when anything
/// was lost; the hint only when fragments failed (not culled or invalid).
void warn_losses(const std::string& command, const Counters& c, const std::string& context,
                 const std::string& hint);

/// Prints "habuffer COMMAND: lossless mode: SUMMARYCONTEXT", the one line of
/// a --lossless run that still lost fragments (it exits 1).
void report_lossless_failure(const std::string& command, const Counters& c, const std::string& context);

}  // namespace habuffer::cli
