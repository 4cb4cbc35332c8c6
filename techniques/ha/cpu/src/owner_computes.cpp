#include "habuffer/techniques/ha/owner_computes.h"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "habuffer/parallel.h"

namespace habuffer {
namespace {

template <class Word>
class OwnerComputes {
  using Kernel = HashKernel<Word, false>;
  using Carry = typename Kernel::HabufferCarry;

  // Everything one owner writes during a round, on cache lines of its own.
  struct alignas(64) Owner {
    std::vector<std::uint32_t> max_age;            // private copy of M
    std::vector<std::vector<Carry>> outbox[2];     // [round parity][destination]
    std::uint64_t tally[HABUFFER_OUTCOME_COUNT] = {};
  };

 public:
  OwnerComputes(const KernelParams& params, const glm::uvec2* offsets, Word* table, MaxAgeTable& max_age,
                const OwnerComputesOptions& options)
      : params_(params), offsets_(offsets), table_(table), max_age_(max_age), options_(options),
        owners_(options.owners),
        band_div_(options.band_rows),
        owner_mod_(options.owners) {
    if (options.owners == 0 || options.band_rows == 0)
      throw std::invalid_argument("owner-computes needs at least one owner and one row per band");
    for (Owner& o : owners_) {
      o.max_age.assign(max_age.ages().size(), 0);
      o.outbox[0].resize(options.owners);
      o.outbox[1].resize(options.owners);
    }
  }

  Counters run(std::span<const Fragment> fragments) {
    for_each_owner([&](std::uint32_t t, Kernel& k) { start(t, k, fragments); });
    for (unsigned round = 0; pending(round); ++round)
      for_each_owner([&](std::uint32_t t, Kernel& k) { deliver(t, k, round); });
    merge_max_age();
    Counters total;
    for (const Owner& o : owners_) total.add_tally(o.tally);
    return total;
  }

 private:
  // Called for every probe: divisions by multiplication.
  std::uint32_t owner_of_row(std::uint32_t hy) const { return owner_mod_.mod(band_div_.div(hy)); }

  template <class F>
  void for_each_owner(F&& f) {
    fork_join(options_.owners, [&](std::uint32_t t) {
      Kernel k(params_, offsets_, table_, owners_[t].max_age.data());
      f(t, k);
    });
  }

  // Out of line and by value, so the carried record never has its address
  // taken in drive() and stays in registers there (measured: 2-3 ms of 15 ms
  // per 2^20 fragments).
  [[gnu::noinline]] static void send(std::vector<Carry>& box, glm::uvec2 p, std::uint32_t a, Word r, float acc,
                                     std::uint32_t iter, Word front) {
    Carry c;
    c.p = p;
    c.a = a;
    c.r = r;
    c.acc = acc;
    c.iter = iter;
    c.front = front;
    box.push_back(c);
  }

  // Runs insert steps while the carried record probes this owner's slots.
  void drive(std::uint32_t t, Kernel& k, Carry c, unsigned parity) {
    Owner& me = owners_[t];
    const bool cull = k.habuffer_cull_tau > 0.0f;
    for (;;) {
      std::uint32_t outcome = k.ha_insert_limit(c);
      if (outcome == HABUFFER_PENDING) {
        const glm::uvec2 h = k.ha_probe(c.p, c.a);
        const std::uint32_t dest = owner_of_row(h.y);
        if (dest != t) {
          send(me.outbox[parity][dest], c.p, c.a, c.r, c.acc, c.iter, c.front);
          return;
        }
        outcome = k.ha_insert_step_at(c, h, cull);
      }
      if (outcome != HABUFFER_PENDING) {
        ++me.tally[outcome];
        return;
      }
    }
  }

  // Round 0: every owner scans the whole stream and starts the fragments
  // whose first probe lands in its bands (invalid ones are counted by the
  // owner their first probe would have reached, so exactly once).
  void start(std::uint32_t t, Kernel& k, std::span<const Fragment> fragments) {
    for (const Fragment& f : fragments) {
      const glm::uvec2 p(f.x, f.y);
      if (owner_of_row(k.ha_probe(p, 1).y) != t) continue;
      if (!k.ha_fragment_valid(f.depth, f.coverage)) {
        ++owners_[t].tally[HABUFFER_INVALID];
        continue;
      }
      drive(t, k, k.habuffer_carry_begin(p, k.ha_fragment_code(f.depth, f.coverage), f.rgba), 0);
    }
  }

  bool pending(unsigned round) const {
    for (const Owner& o : owners_)
      for (const auto& box : o.outbox[round & 1])
        if (!box.empty()) return true;
    return false;
  }

  // Consumes the messages sent to t in the previous round; new messages go
  // to the other parity, which nobody reads during this round.
  void deliver(std::uint32_t t, Kernel& k, unsigned round) {
    for (Owner& src : owners_) {
      auto& box = src.outbox[round & 1][t];
      for (const Carry& c : box) drive(t, k, c, (round + 1) & 1);
      box.clear();
    }
  }

  void merge_max_age() {
    std::uint32_t* m = max_age_.data();
    const std::size_t cells = max_age_.ages().size();
    const std::uint32_t parts = options_.owners;
    fork_join(parts, [&](std::uint32_t part) {
      for (std::size_t c = cells * part / parts; c < cells * (part + 1) / parts; ++c)
        for (const Owner& o : owners_) m[c] = std::max(m[c], o.max_age[c]);
    });
  }

  const KernelParams& params_;
  const glm::uvec2* offsets_;
  Word* table_;
  MaxAgeTable& max_age_;
  OwnerComputesOptions options_;
  std::vector<Owner> owners_;
  FastDivisor band_div_;
  FastDivisor owner_mod_;
};

}  // namespace

template <class Word>
Counters insert_owner_computes(const KernelParams& params, const glm::uvec2* offsets, Word* table,
                               MaxAgeTable& max_age, std::span<const Fragment> fragments,
                               const OwnerComputesOptions& options) {
  return OwnerComputes<Word>(params, offsets, table, max_age, options).run(fragments);
}

template Counters insert_owner_computes<std::uint64_t>(const KernelParams&, const glm::uvec2*, std::uint64_t*,
                                                       MaxAgeTable&, std::span<const Fragment>,
                                                       const OwnerComputesOptions&);
template Counters insert_owner_computes<std::uint32_t>(const KernelParams&, const glm::uvec2*, std::uint32_t*,
                                                       MaxAgeTable&, std::span<const Fragment>,
                                                       const OwnerComputesOptions&);

}  // namespace habuffer
