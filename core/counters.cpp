#include "habuffer/counters.h"

namespace habuffer {

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

}  // namespace habuffer
