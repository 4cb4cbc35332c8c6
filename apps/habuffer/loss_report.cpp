#include "loss_report.h"

#include <cstdio>

namespace habuffer::cli {

namespace {

// The kinds of outcome that leave a fragment out of the lists, in the order
// the summary names them: losses first, then what was hidden, then refusals.
constexpr CounterKind kNotStored[] = {CounterKind::Failure, CounterKind::Hidden, CounterKind::Invalid};

}  // namespace

std::uint64_t lost_fragments(const Counters& c) {
  std::uint64_t n = 0;
  for (const CounterKind kind : kNotStored)
    for (const CounterField& f : kCounterFields)
      if (f.kind == kind) n += c.*f.member;
  return n;
}

std::string loss_summary(const Counters& c) {
  std::string s = std::to_string(lost_fragments(c)) + " of " + std::to_string(c.fragments) + " fragments not stored:";
  bool first = true;
  for (const CounterKind kind : kNotStored)
    for (const CounterField& f : kCounterFields) {
      if (f.kind != kind || c.*f.member == 0) continue;
      s += first ? " " : ", ";
      s += f.name;
      if (!f.reason.empty()) s += " (" + std::string(f.reason) + ")";
      s += ' ';
      s += std::to_string(c.*f.member);
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
