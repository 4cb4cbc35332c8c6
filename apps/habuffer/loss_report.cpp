#include "loss_report.h"

#include <cstdio>

namespace habuffer::cli {

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
