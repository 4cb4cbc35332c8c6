/// @file
/// Losses said out loud: any run whose fragments did not all end stored or
/// merged as duplicates prints one warning line on stderr with the counts,
/// whether or not a stats file was asked for (SPEC invariant 1).
#pragma once

#include <cstdint>
#include <string>

#include "habuffer/fragment.h"
#include "habuffer/technique.h"

namespace habuffer::cli {

/// Fragments that are not in the table and not a duplicate of one that is:
/// failed (age or iteration limit), culled by early cull, or invalid.
std::uint64_t lost_fragments(const Counters& c);

/// "19745 of 20000 fragments not stored: failed_age 19745, culled 3" (only
/// the non-zero reasons).
std::string loss_summary(const Counters& c);

/// What to try when fragments failed in a command that takes --lossless.
inline constexpr const char* kLosslessHint =
    "--lossless grows the table until they fit (or give a larger --table, more --age-bits)";
/// What keeps a technique's dropped fragments (empty for wboit and blend, which keep no lists).
inline const char* lossless_hint(Technique t) {
  switch (t) {
    case Technique::Ha: return kLosslessHint;
    case Technique::Lists: return "--lossless grows the node pool until they fit (or give a larger --pool)";
    case Technique::SortedLists: return "--lossless grows the node pool until they fit (or give a larger --pool)";
    case Technique::Arrays: return "--lossless raises K to the deepest pixel (or give more --layers)";
    case Technique::KBuffer: return "the k-buffer keeps the K nearest by design: --lossless doubles K until nothing drops";
    case Technique::Wboit:
    case Technique::Blend: return "";
  }
  return kLosslessHint;
}

/// Prints "habuffer COMMAND: warning: SUMMARY[CONTEXT][; HINT]" when anything
/// was lost; the hint only when fragments failed (not culled or invalid).
void warn_losses(const std::string& command, const Counters& c, const std::string& context,
                 const std::string& hint);

/// Prints "habuffer COMMAND: lossless mode: SUMMARYCONTEXT", the one line of
/// a --lossless run that still lost fragments (it exits 1).
void report_lossless_failure(const std::string& command, const Counters& c, const std::string& context);

}  // namespace habuffer::cli
