#include "loss_report.h"

#include <cstdio>

namespace habuffer::cli {

std::uint64_t lost_fragments(const Counters& c) { return c.failures() + c.culled + c.saturated_rejected + c.invalid; }

std::string loss_summary(const Counters& c) {
  std::string s = std::to_string(lost_fragments(c)) + " of " + std::to_string(c.fragments) + " fragments not stored:";
  const std::pair<const char*, std::uint64_t> reasons[] = {{"failed_age", c.failed_age},
                                                           {"failed_iter", c.failed_iter},
                                                           {"dropped_pool (node pool full)", c.dropped_pool},
                                                           {"dropped_layers (pixel's layers full)", c.dropped_layers},
                                                           {"occupancy_rejected (beyond the k nearest)", c.occupancy_rejected},
                                                           {"culled (early cull)", c.culled},
                                                           {"saturated_rejected (behind a culled fragment)", c.saturated_rejected},
                                                           {"invalid (depth NaN or outside [0, 1])", c.invalid}};
  bool first = true;
  for (const auto& [name, n] : reasons) {
    if (n == 0) continue;
    s += first ? " " : ", ";
    s += name;
    s += ' ';
    s += std::to_string(n);
    first = false;
  }
  return s;
}

void warn_losses(const std::string& command, const Counters& c, const std::string& context,
                 const std::string& hint) {
  if (lost_fragments(c) == 0) return;
  std::string line = "habuffer " + command + ": warning: " + loss_summary(c) + context;
  if (c.failures() > 0 && !hint.empty()) line += "; " + hint;
  std::fprintf(stderr, "%s\n", line.c_str());
}

void report_lossless_failure(const std::string& command, const Counters& c, const std::string& context) {
  std::fprintf(stderr, "habuffer %s: lossless mode: %s%s\n", command.c_str(), loss_summary(c).c_str(),
               context.c_str());
}

}  // namespace habuffer::cli
