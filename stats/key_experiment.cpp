#include "habuffer/key_experiment.h"

#include "named_list.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "habuffer/age_experiment.h"

namespace habuffer::spatial {
namespace {

// A record: its age (0: empty) and its key's folded coordinates.
struct Slot {
  std::uint32_t age = 0;
  std::uint32_t u = 0, v = 0;
};

// The order the spatial hash's records have between keys: age, then the
// quotient (which orders the keys of one position as (v / Hy, u / Hx)).
struct Table {
  Extent h;
  std::uint32_t qx = 1, amax = 255, block = 8, cells_x = 1;
  const OffsetSequence* offsets = nullptr;
  KeyProbing probing = KeyProbing::Coherent;
  KeyPolicy policy = KeyPolicy::RobinHood;
  std::uint64_t seed = 1;
  std::vector<Slot> slots;
  std::vector<std::uint32_t> max_age;

  [[nodiscard]] std::uint32_t quotient(const Slot& s) const { return s.u / h.x + qx * (s.v / h.y); }
  // Whether record a keeps a slot against b: the larger age, then (as the
  // spatial hash's records order) the larger quotient; under independent
  // probing two keys of one age may share a slot and a quotient, so the key
  // itself decides.
  [[nodiscard]] bool beats(const Slot& a, const Slot& b) const {
    if (a.age != b.age) return a.age > b.age;
    if (probing == KeyProbing::Coherent) return quotient(a) > quotient(b);
    return a.v != b.v ? a.v > b.v : a.u > b.u;
  }
  [[nodiscard]] glm::uvec2 position(const Slot& s) const { return {s.u % h.x, s.v % h.y}; }
  [[nodiscard]] std::uint64_t probe(const Slot& s, std::uint32_t age) const {
    if (probing == KeyProbing::Coherent) {
      const glm::uvec2 p = position(s), o = (*offsets)[age - 1];
      return (p.x + o.x) % h.x + std::uint64_t{(p.y + o.y) % h.y} * h.x;
    }
    // splitmix64 of (key, age, seed): an independent slot per age.
    std::uint64_t z = (std::uint64_t{s.u} << 32 | s.v) ^ (std::uint64_t{age} * 0x9E3779B97F4A7C15ull) ^ seed;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return (z ^ (z >> 31)) % h.area();
  }
  [[nodiscard]] std::uint32_t cell(const Slot& s) const {
    const glm::uvec2 p = position(s);
    return p.x / block + (p.y / block) * cells_x;
  }
  // Inserts a key not in the table; false when a record went past AMAX.
  bool insert(Slot r) {
    r.age = 1;
    while (true) {
      if (r.age > amax) return false;
      Slot& s = slots[probe(r, r.age)];
      if (s.age == 0 || (policy == KeyPolicy::RobinHood && beats(r, s))) {
        max_age[cell(r)] = std::max(max_age[cell(r)], r.age);
        const Slot old = s;
        s = r;
        if (old.age == 0) return true;
        r = old;
      }
      ++r.age;
    }
  }
  // Slots a lookup of `k` reads (present or not).
  [[nodiscard]] std::uint32_t reads(Slot k) const {
    const std::uint32_t bound = max_age[cell(k)];
    std::uint32_t n = 0;
    for (std::uint32_t a = 1; a <= bound; ++a) {
      k.age = a;
      const Slot& s = slots[probe(k, a)];
      ++n;
      if (s.age == a && s.u == k.u && s.v == k.v) break;
      if (s.age == 0) break;
      if (policy == KeyPolicy::RobinHood && beats(k, s)) break;
    }
    return n;
  }
};

// An empty table of `h` slots over `fold`'s domain.
Table empty_table(const FoldedDomain& fold, Extent h, std::uint32_t age_bits, std::uint32_t block,
                  const OffsetSequence& offsets, KeyProbing probing, KeyPolicy policy, std::uint64_t seed) {
  Table t;
  t.h = h;
  t.qx = (fold.folded().x + h.x - 1) / h.x;
  t.amax = (1u << age_bits) - 1;
  t.block = block;
  t.cells_x = (h.x + block - 1) / block;
  t.offsets = &offsets;
  t.probing = probing;
  t.policy = policy;
  t.seed = seed;
  t.slots.assign(h.area(), Slot{});
  t.max_age.assign(std::uint64_t{t.cells_x} * ((h.y + block - 1) / block), 0);
  return t;
}


}  // namespace

void KeyExperimentConfig::validate() const {
  keys.validate();
  if (loads.empty()) throw std::invalid_argument("key experiment: no loads");
  for (const double l : loads)
    if (!(l > 0.0 && l <= 1.0)) throw std::invalid_argument("key experiment: load " + std::to_string(l) + " outside (0, 1]");
  if (trials == 0 || trials > 1000) throw std::invalid_argument("key experiment: trials " + std::to_string(trials) + " outside 1..1000");
  if (probing.empty() || policy.empty()) throw std::invalid_argument("key experiment: no variant");
  if (age_bits < 4 || age_bits > 12) throw std::invalid_argument("key experiment: age bits " + std::to_string(age_bits) + " outside 4..12");
  if (block == 0) throw std::invalid_argument("key experiment: block 0");
}

std::vector<std::uint64_t> simulate_coherent_robin_hood(const std::vector<glm::uvec3>& keys, Domain domain,
                                                        Extent table, std::uint32_t age_bits,
                                                        const OffsetSequence& offsets) {
  const FoldedDomain fold(domain);
  Table t = empty_table(fold, table, age_bits, 8, offsets, KeyProbing::Coherent, KeyPolicy::RobinHood, 0);
  for (const glm::uvec3 k : keys) {
    const glm::uvec2 f = fold.fold(k);
    if (!t.insert({1, f.x, f.y})) throw std::runtime_error("simulator: a key went past AMAX");
  }
  std::vector<std::uint64_t> out(t.slots.size(), 0);
  for (std::size_t s = 0; s < out.size(); ++s)
    if (t.slots[s].age != 0)
      out[s] = (std::uint64_t{(t.slots[s].age << (32u - age_bits)) | (t.quotient(t.slots[s]) << 1) | 1u}) << 32;
  return out;
}

namespace {

// One variant at one load, over the trials.
struct KeyAccumulator {
  Moments age, max_age, stored, miss, fail, nkeys;
  std::uint32_t largest = 0;
};

// One trial's inputs, the same for every variant and load: its key set, the
// order they are inserted in, and the absent keys looked up.
struct KeyTrialInputs {
  std::vector<glm::uvec3> keys, order, absent;
};

KeyTrialInputs trial_inputs(const KeyExperimentConfig& c, std::uint32_t trial) {
  KeySetOptions o = c.keys;
  o.seed = c.keys.seed + trial;
  KeyTrialInputs in;
  in.keys = make_keys(o);
  in.order = ordered(in.keys, KeyOrder::Shuffled, c.seed + trial);
  const std::uint64_t free_points = std::uint64_t{o.domain.x} * o.domain.y * o.domain.z - in.keys.size();
  const std::uint64_t want = std::min<std::uint64_t>(c.misses, free_points / 2);
  if (want) in.absent = absent_keys(in.keys, o.domain, want, c.seed + 7 * trial);
  return in;
}

// One variant's table for the trial's keys (on table h with its offsets), measured into `a`.
void run_variant(const KeyExperimentConfig& c, const KeyTrialInputs& in, const FoldedDomain& fold, Extent h,
                 const OffsetSequence& offsets, KeyProbing probing, KeyPolicy policy, std::uint32_t trial,
                 KeyAccumulator& a) {
  Table t = empty_table(fold, h, c.age_bits, c.block, offsets, probing, policy, c.seed * 0x9E3779B97F4A7C15ull + trial);
  std::uint64_t failed = 0;
  for (const glm::uvec3 k : in.order) {
    const glm::uvec2 f = fold.fold(k);
    failed += t.insert({1, f.x, f.y}) ? 0 : 1;
  }
  double sum = 0;
  std::uint32_t largest = 0;
  std::uint64_t records = 0;
  for (const Slot& s : t.slots)
    if (s.age != 0) {
      sum += s.age;
      largest = std::max(largest, s.age);
      ++records;
    }
  double reads = 0;
  for (const glm::uvec3 k : in.absent) {
    const glm::uvec2 f = fold.fold(k);
    reads += t.reads({1, f.x, f.y});
  }
  a.age.add(records ? sum / static_cast<double>(records) : 0.0);
  a.max_age.add(largest);
  a.largest = std::max(a.largest, largest);
  a.stored.add(static_cast<double>(records) / static_cast<double>(h.area()));
  a.fail.add(static_cast<double>(failed));
  a.nkeys.add(static_cast<double>(in.keys.size()));
  a.miss.add(in.absent.empty() ? 0.0 : reads / static_cast<double>(in.absent.size()));
}

KeyExperimentRow key_row(const KeyExperimentConfig& c, KeyProbing probing, KeyPolicy policy, double load,
                         const KeyAccumulator& a) {
  KeyExperimentRow row;
  row.variant = std::string(probing == KeyProbing::Coherent ? "coherent" : "independent") + "/" +
                (policy == KeyPolicy::RobinHood ? "robinhood" : "firstcome");
  row.load = load;
  row.max_age = a.largest;
  row.trials = c.trials;
  row.keys = a.nkeys.mean();
  row.stored_load = a.stored.mean();
  row.mean_age = a.age.mean();
  row.mean_age_ci95 = a.age.ci95();
  row.mean_max_age = a.max_age.mean();
  row.hit_reads = row.mean_age;  // a present key is read at its age
  row.miss_reads = a.miss.mean();
  row.miss_reads_ci95 = a.miss.ci95();
  row.failures = a.fail.mean();
  return row;
}

}  // namespace

std::vector<KeyProbing> parse_key_probings(const std::vector<std::string>& names) {
  static constexpr std::pair<std::string_view, KeyProbing> kNames[] = {{"coherent", KeyProbing::Coherent},
                                                                       {"independent", KeyProbing::Independent}};
  return habuffer::detail::named_list<KeyProbing>(names, kNames);
}

std::vector<KeyPolicy> parse_key_policies(const std::vector<std::string>& names) {
  static constexpr std::pair<std::string_view, KeyPolicy> kNames[] = {{"robinhood", KeyPolicy::RobinHood},
                                                                      {"fcfs", KeyPolicy::FirstCome}};
  return habuffer::detail::named_list<KeyPolicy>(names, kNames);
}

std::vector<KeyExperimentRow> run_key_experiment(const KeyExperimentConfig& c) {
  c.validate();
  // Trials outermost: a trial's key set, order and absent keys are made once
  // for every variant and load (each accumulator still sees trials in order).
  const std::size_t variants = c.probing.size() * c.policy.size();
  std::vector<KeyAccumulator> acc(variants * c.loads.size());
  const FoldedDomain fold(c.keys.domain);
  for (std::uint32_t trial = 0; trial < c.trials; ++trial) {
    const KeyTrialInputs in = trial_inputs(c, trial);
    for (std::size_t l = 0; l < c.loads.size(); ++l) {
      const Extent h = SpatialHash::table_for(fold, c.age_bits, in.keys.size(), c.loads[l]);
      const OffsetSequence offsets = OffsetSequence::random(h, (1u << c.age_bits) - 1, c.seed + trial);
      for (std::size_t p = 0; p < c.probing.size(); ++p)
        for (std::size_t q = 0; q < c.policy.size(); ++q)
          run_variant(c, in, fold, h, offsets, c.probing[p], c.policy[q], trial,
                      acc[(p * c.policy.size() + q) * c.loads.size() + l]);
    }
  }
  std::vector<KeyExperimentRow> rows;
  for (std::size_t p = 0; p < c.probing.size(); ++p)
    for (std::size_t q = 0; q < c.policy.size(); ++q)
      for (std::size_t l = 0; l < c.loads.size(); ++l)
        rows.push_back(key_row(c, c.probing[p], c.policy[q], c.loads[l], acc[(p * c.policy.size() + q) * c.loads.size() + l]));
  return rows;
}

}  // namespace habuffer::spatial
