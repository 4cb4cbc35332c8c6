#include "habuffer/counters.h"

namespace habuffer {
namespace {

// The kinds of outcome that leave a fragment out of the lists, in the order
// the summary names them: losses first, then what was hidden, then refusals.
constexpr CounterKind kNotStored[] = {CounterKind::Failure, CounterKind::Hidden, CounterKind::Invalid};

}  // namespace

std::uint64_t Counters::failures() const {
  std::uint64_t n = 0;
  for (const CounterField& f : kCounterFields)
    if (f.kind == CounterKind::Failure) n += this->*f.member;
  return n;
}

std::uint64_t Counters::stored() const {
  std::uint64_t n = fragments;
  for (const CounterField& f : kCounterFields) n -= this->*f.member;
  return n;
}

void Counters::count(std::uint32_t outcome) {
  ++fragments;
  for (const CounterField& f : kCounterFields)
    if (f.outcome == outcome) ++(this->*f.member);
}

void Counters::add_tally(const std::uint64_t* tally) {
  for (std::uint32_t o = 0; o < HABUFFER_OUTCOME_COUNT; ++o) fragments += tally[o];
  for (const CounterField& f : kCounterFields) this->*f.member += tally[f.outcome];
}

Counters& Counters::operator+=(const Counters& o) {
  fragments += o.fragments;
  for (const CounterField& f : kCounterFields) this->*f.member += o.*f.member;
  return *this;
}

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

}  // namespace habuffer
