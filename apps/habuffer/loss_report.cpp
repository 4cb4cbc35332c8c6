#include "loss_report.h"

#include <cstdio>

namespace habuffer::cli {

void warn_losses(const std::string& who, const Counters& c, const std::string& context, const std::string& hint) {
  if (lost_fragments(c) == 0) return;
  std::string line = who + ": warning: " + loss_summary(c) + context;
  if (c.failures() > 0 && !hint.empty()) line += "; " + hint;
  std::fprintf(stderr, "%s\n", line.c_str());
}

void report_lossless_failure(const std::string& who, const Counters& c, const std::string& context) {
  std::fprintf(stderr, "%s: lossless mode: %s%s\n", who.c_str(), loss_summary(c).c_str(), context.c_str());
}

std::string lossless_failure_reason(const std::string& too_deep, bool growth_limited, std::uint32_t max_attempts,
                                    Technique t) {
  if (!too_deep.empty()) return ": " + too_deep;
  if (growth_limited) return " (the technique's buffers reached this OpenGL's limits)";
  if (max_attempts == 1) return "; one attempt grows nothing: allow more --max-attempts";
  return uses_table(t) ? "; more --age-bits fits deeper pixels" : "";
}

}  // namespace habuffer::cli
