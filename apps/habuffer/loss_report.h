// Losses said out loud: any run whose fragments did not all end stored or
// merged as duplicates prints one warning line on stderr with the counts,
// whether or not a stats file was asked for (SPEC invariant 1).
#pragma once

#include <cstdint>
#include <string>

#include "habuffer/fragment.h"

namespace habuffer::cli {

// Fragments that are not in the table and not a duplicate of one that is:
// failed (age or iteration limit), culled by early cull, or invalid.
std::uint64_t lost_fragments(const Counters& c);

// "19745 of 20000 fragments not stored: failed_age 19745, culled 3" (only
// the non-zero reasons).
std::string loss_summary(const Counters& c);

// Prints "habuffer COMMAND: warning: SUMMARY[; HINT]" when anything was lost.
void warn_losses(const std::string& command, const Counters& c, const std::string& hint = {});

// What to try when fragments failed (not culled or invalid).
std::string failure_hint(bool lossless);

}  // namespace habuffer::cli
