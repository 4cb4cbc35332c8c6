#include "habuffer/technique_frames.h"

#include "habuffer/attempt_need.h"

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <utility>


namespace habuffer {
namespace {

// Whether `buffer` is the container make_fragment_buffer would make for `c`
// (the offsets come from one source, so the configuration says it all).
bool made_for(const FragmentBuffer& buffer, const TechniqueConfig& c) {
  return buffer.technique_config().relevant() == c.relevant();
}

}  // namespace

GrowthNeed attempt_need(const FragmentBuffer& buffer, const Counters& counters) {
  GrowthNeed need = buffer.growth_need();
  need.records = counters.records_needed();
  return need;
}

TechniqueFrames::TechniqueFrames(OffsetSource offsets, InsertOptions options, ResizePolicy policy,
                                 std::uint32_t max_attempts)
    : offsets_(std::move(offsets)), options_(options), policy_(policy), max_attempts_(max_attempts) {
  if (max_attempts == 0) throw std::invalid_argument("at least one build attempt is needed");
  policy.validate();
}

std::unique_ptr<FragmentBuffer> TechniqueFrames::container_for(const TechniqueConfig& c) {
  if (last_ && last_->buffer && made_for(*last_->buffer, c)) {
    std::unique_ptr<FragmentBuffer> kept = std::move(last_->buffer);
    kept->reset();
    return kept;
  }
  std::unique_ptr<FragmentBuffer> made = make_fragment_buffer(c, offsets_);
  ++made_;
  return made;
}

const TechniqueBuild& TechniqueFrames::build(const TechniqueConfig& config, std::span<const Fragment> fragments) {
  TechniqueConfig c = config;
  c.buffer.table = config.buffer.table_or_screen();
  // The automatic pool (0), as render's --pool auto: the fragments at
  // grow_at use, and grown at once (one more attempt) when that drops, as
  // render's automatic pool is: a technique may need more nodes than
  // fragments (paged lists take whole pages).
  const bool automatic_pool = uses_pool(c.technique) && c.pool_capacity == 0;
  if (automatic_pool) c.pool_capacity = policy_.automatic(fragments.size());
  std::uint32_t attempts = automatic_pool ? std::max<std::uint32_t>(max_attempts_, 2) : max_attempts_;
  bool rule_asked = false;  // lossless_attempts, asked once: after the first failed attempt
  auto b = std::make_unique<TechniqueBuild>();
  std::uint64_t sized_for = 0;  // the count the next attempt is sized by
  for (;;) {
    const auto t0 = std::chrono::steady_clock::now();
    std::unique_ptr<FragmentBuffer> buffer = container_for(c);
    last_.reset();  // a failed attempt's container is not kept: the next is larger
    const Counters counters = buffer->insert(fragments, options_);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    b->attempts.push_back(
        {uses_table(c.technique) ? c.buffer.table : Extent{}, counters, buffer->capacity(), sized_for, ms});
    b->counters = counters;
    b->buffer = std::move(buffer);
    if (counters.failures() == 0 || b->attempts.size() >= attempts) break;
    // Lossless mode's rule of every path (the GPU's asks it before its first
    // gather): no growth where growing cannot help.
    if (!rule_asked) {
      rule_asked = true;
      AttemptLimit limit = lossless_attempts(c, fragments, attempts);
      attempts = limit.attempts;
      b->too_deep = std::move(limit.too_deep);
      if (b->attempts.size() >= attempts) break;
    }
    // The lossless attempt after a drop, sized by what this one counted.
    const GrowthNeed need = attempt_need(*b->buffer, b->counters);
    const TechniqueConfig next = c.grown(policy_, need);
    sized_for = need.count_for(c.technique);
    if (!next.limit().empty()) {  // no larger buffer can be built: the last attempt's result, marked
      b->growth_limited = true;
      break;
    }
    c = next;
  }
  last_ = std::move(b);
  return *last_;
}

const TechniqueBuild& TechniqueFrames::last() const {
  if (!last_) throw std::logic_error("TechniqueFrames::last() before the first frame");
  return *last_;
}

TechniqueBuild TechniqueFrames::release() {
  if (!last_) throw std::logic_error("TechniqueFrames::release() before the first frame");
  TechniqueBuild b = std::move(*last_);
  last_.reset();
  return b;
}

}  // namespace habuffer
