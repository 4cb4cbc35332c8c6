#include "habuffer/spatial/spatial_hash.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "habuffer/memory_budget.h"
#include "habuffer/parallel.h"
#include "habuffer/spatial/spatial_hash_kernel.h"

namespace habuffer::spatial {
namespace {

constexpr std::uint64_t kNoSlot = ~std::uint64_t{0};
// Below this many records a pass runs on the calling thread: forking costs more.
constexpr std::size_t kParallelMin = 1u << 13;

std::uint32_t ceil_div(std::uint64_t a, std::uint64_t b) { return static_cast<std::uint32_t>((a + b - 1) / b); }

std::string key_text(glm::uvec3 k) {
  std::string s = "(";
  s += std::to_string(k.x) + ", " + std::to_string(k.y) + ", " + std::to_string(k.z) + ")";
  return s;
}

// Whether the quotients of a table fit the record's 31 - A bits.
bool quotients_fit(Extent folded, Extent table, std::uint32_t age_bits) {
  const std::uint64_t q = std::uint64_t{ceil_div(folded.x, table.x)} * ceil_div(folded.y, table.y);
  return q <= (std::uint64_t{1} << (31u - age_bits));
}

std::uint32_t bits_for(std::uint64_t count) {
  std::uint32_t b = 0;
  while ((std::uint64_t{1} << b) < count) ++b;
  return b;
}

// 25 % more area, the aspect kept, at most the domain.
Extent grown(Extent t, Extent folded) {
  const double f = std::sqrt(1.25);
  return {static_cast<std::uint32_t>(std::min<double>(folded.x, std::ceil(t.x * f))),
          static_cast<std::uint32_t>(std::min<double>(folded.y, std::ceil(t.y * f)))};
}

}  // namespace

std::string Domain::str() const {
  std::string s = std::to_string(x) + "x" + std::to_string(y);
  if (z != 1) {
    s += 'x';
    s += std::to_string(z);
  }
  return s;
}

FoldedDomain::FoldedDomain(Domain d) : domain_(d) {
  if (d.x == 0 || d.y == 0 || d.z == 0)
    throw std::invalid_argument("spatial hash: domain " + d.str() + " has a zero side");
  // G slices interleaved along x, G a power of two (x-neighbours G slots apart, z-neighbours of
  // a group adjacent: a 3D neighbourhood within a few cache lines), then F
  // groups per row, so that Dx G F and Dy ceil(groups / F) are about equal.
  while ((2u << shift_) <= std::min<std::uint32_t>(d.z, kInterleave)) ++shift_;
  const std::uint32_t interleave = 1u << shift_;
  const std::uint64_t groups = ceil_div(d.z, interleave), width = std::uint64_t{d.x} * interleave;
  const double f = std::sqrt(static_cast<double>(groups) * d.y / static_cast<double>(width));
  per_row_ = static_cast<std::uint32_t>(std::clamp(std::llround(f), 1LL, static_cast<long long>(groups)));
  rows_ = FastDivisor(per_row_);
  const std::uint64_t u = width * per_row_, v = std::uint64_t{d.y} * ceil_div(groups, per_row_);
  if (u > std::numeric_limits<std::uint32_t>::max() || v > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("spatial hash: domain " + d.str() + " folds to " + std::to_string(u) + "x" +
                                std::to_string(v) + ", beyond 32-bit coordinates");
  folded_ = {static_cast<std::uint32_t>(u), static_cast<std::uint32_t>(v)};
}

std::string to_string(DuplicateRule rule) {
  switch (rule) {
    case DuplicateRule::Max: return "max";
    case DuplicateRule::Min: return "min";
    case DuplicateRule::First: return "first";
    case DuplicateRule::Last: return "last";
  }
  return "?";
}

std::optional<DuplicateRule> parse_duplicate_rule(const std::string& text) {
  for (const DuplicateRule r : {DuplicateRule::Max, DuplicateRule::Min, DuplicateRule::First, DuplicateRule::Last})
    if (to_string(r) == text) return r;
  return std::nullopt;
}

void SpatialHashConfig::validate() const {
  (void)FoldedDomain(domain);
  const auto bad = [](const std::string& what) { throw std::invalid_argument("spatial hash: " + what); };
  if (age_bits < HABUFFER_SH_MIN_AGE_BITS || age_bits > HABUFFER_SH_MAX_AGE_BITS)
    bad("age bits " + std::to_string(age_bits) + " outside " + std::to_string(HABUFFER_SH_MIN_AGE_BITS) + ".." +
        std::to_string(HABUFFER_SH_MAX_AGE_BITS));
  if (block == 0 || block > 4096) bad("max-age block " + std::to_string(block) + " outside 1..4096");
  if (offsets == OffsetGenerator::List) bad("offsets must be random or farthest (a list is made for one table size)");
  if (!(target_load > 0.0 && target_load <= 1.0)) bad("target load " + std::to_string(target_load) + " outside (0, 1]");
  if (!(grow_at > 0.0 && grow_at <= 1.0)) bad("grow_at " + std::to_string(grow_at) + " outside (0, 1]");
  if (!(shrink_at >= 0.0 && shrink_at < grow_at))
    bad("shrink_at " + std::to_string(shrink_at) + " outside [0, grow_at = " + std::to_string(grow_at) + ")");
  if (iter_limit == 0) bad("iteration limit 0");
  if (miss_filter_bits != 0 && miss_filter_bits != 8 && miss_filter_bits != 16)
    bad("miss filter bits " + std::to_string(miss_filter_bits) + " not 0, 8 or 16");
  if (max_growths > 64) bad("max_growths " + std::to_string(max_growths) + " above 64");
  if (threads > kMaxThreads) bad("threads " + std::to_string(threads) + " outside 0.." + std::to_string(kMaxThreads));
}

InsertReport& InsertReport::operator+=(const InsertReport& o) {
  calls += o.calls;
  stored += o.stored;
  duplicates += o.duplicates;
  failed_age += o.failed_age;
  failed_iter += o.failed_iter;
  lost += o.lost;
  tombstones_dropped += o.tombstones_dropped;
  rehashes += o.rehashes;
  return *this;
}

Extent SpatialHash::table_for(const FoldedDomain& fold, std::uint32_t age_bits, std::uint64_t keys, double load) {
  if (!(load > 0.0 && load <= 1.0)) throw std::invalid_argument("spatial hash: load " + std::to_string(load) + " outside (0, 1]");
  const Extent d = fold.folded();
  const double wanted = std::max(1.0, std::ceil(static_cast<double>(keys) / load));
  Extent t = d;
  if (wanted < static_cast<double>(d.area())) {
    const double x = std::round(std::sqrt(wanted * d.x / d.y));
    t.x = static_cast<std::uint32_t>(std::clamp(x, 1.0, static_cast<double>(d.x)));
    t.y = static_cast<std::uint32_t>(std::clamp(std::ceil(wanted / t.x), 1.0, static_cast<double>(d.y)));
    if (static_cast<double>(t.area()) < wanted)
      t.x = static_cast<std::uint32_t>(std::min(static_cast<double>(d.x), std::ceil(wanted / t.y)));
  }
  const Extent for_load = t;
  while (!quotients_fit(d, t, age_bits)) t = grown(t, d);
  if (t.area() > kMaxSlots) {
    if (t == for_load)
      throw std::invalid_argument("spatial hash: " + std::to_string(keys) + " keys at load " + std::to_string(load) +
                                  " need a table of " + t.str() + " slots, above the " + std::to_string(kMaxSlots) +
                                  "-slot limit");
    throw std::invalid_argument("spatial hash: the domain " + fold.domain().str() + " needs a table of at least " +
                                t.str() + " slots for its quotients to fit " + std::to_string(31u - age_bits) +
                                " bits (" + std::to_string(age_bits) + " age bits), above the " +
                                std::to_string(kMaxSlots) + "-slot limit: use fewer age bits or a smaller domain");
  }
  return t;
}

std::uint64_t SpatialHash::memory_for(const SpatialHashConfig& config, Extent table) {
  const std::uint32_t block = std::max(config.block, 1u);  // (unchecked configs too: no division by 0)
  const std::uint64_t cells = saturating_product(ceil_div(table.x, block), ceil_div(table.y, block));
  const std::uint64_t amax = (std::uint64_t{1} << std::min(config.age_bits, 32u)) - 1u;
  const std::uint64_t parts[] = {saturating_product(table.area(), sizeof(std::uint64_t)),
                                 saturating_product(cells, sizeof(std::uint32_t)), amax * sizeof(glm::uvec2),
                                 saturating_product(SpatialKernelParams::filter_words_for(table, config.miss_filter_bits),
                                                    sizeof(std::uint32_t))};
  constexpr std::uint64_t kAll = std::numeric_limits<std::uint64_t>::max();
  std::uint64_t sum = 0;
  for (const std::uint64_t p : parts) sum = p > kAll - sum ? kAll : sum + p;
  return sum;
}

SpatialHash::SpatialHash(SpatialHashConfig config, std::uint64_t capacity) : config_(config) {
  config_.validate();
  fold_ = FoldedDomain(config_.domain);
  reset(table_for(fold_, config_.age_bits, capacity, config_.target_load));
}

SpatialHash SpatialHash::restore(SpatialHashConfig config, Extent table, std::vector<std::uint64_t> slots,
                                 std::vector<std::uint32_t> max_age) {
  config.validate();
  const Extent d = FoldedDomain(config.domain).folded();
  const auto bad = [](const std::string& what) { throw std::invalid_argument("spatial hash: " + what); };
  if (table.x == 0 || table.y == 0 || table.x > d.x || table.y > d.y)
    bad("table " + table.str() + " is not within the folded domain " + d.str());
  if (!quotients_fit(d, table, config.age_bits))
    bad("table " + table.str() + " leaves quotients wider than the record's bits for domain " + config.domain.str());
  if (slots.size() != table.area()) bad(std::to_string(slots.size()) + " slots for a table of " + table.str());
  SpatialHash h(config, table, true);
  if (max_age.size() != h.max_age_.size())
    bad(std::to_string(max_age.size()) + " max-age cells for a table of " + table.str() + " (" +
        std::to_string(h.max_age_.size()) + " expected)");
  h.table_ = std::move(slots);
  h.max_age_ = std::move(max_age);
  SpatialHashKernel<false> k = h.reader();
  const std::uint64_t quotients = std::uint64_t{h.quotient_x_} * ceil_div(d.y, table.y);
  const std::uint32_t amax = (1u << config.age_bits) - 1u;
  for (std::uint64_t s = 0; s < h.table_.size(); ++s) {
    const std::uint64_t r = h.table_[s];
    if (r == 0) continue;
    const std::uint32_t age = k.sh_age(r), q = k.sh_quotient(r);
    const std::string where = "slot " + std::to_string(s) + ": ";
    if (age == 0 || age > amax) bad(where + "age " + std::to_string(age) + " outside 1.." + std::to_string(amax));
    if (q >= quotients) bad(where + "quotient " + std::to_string(q) + " of " + std::to_string(quotients));
    if (k.sh_live(r) == 0u && k.sh_value(r) != 0u) bad(where + "a tombstone with a value");
    const glm::uvec2 key = k.sh_record_key(s, r);
    const glm::uvec2 pos = k.sh_position(key);
    if (key.x >= d.x || key.y >= d.y || !h.fold_.contains(h.fold_.unfold(key)))
      bad(where + "its key lies outside the domain " + config.domain.str());
    if (h.max_age_[k.ha_cell(pos)] < age)
      bad(where + "age " + std::to_string(age) + " beyond its max-age cell's " + std::to_string(h.max_age_[k.ha_cell(pos)]));
    if (k.sh_live(r) != 0u) ++h.live_;
    else ++h.tombstones_;
  }
  for (const std::uint32_t cell : h.max_age_)
    if (cell > amax) bad("a max-age cell of " + std::to_string(cell) + " beyond AMAX " + std::to_string(amax));
  h.fill_filter();
  // Every record where a lookup finds it: the Robin Hood order holds, and no key is there twice.
  for (std::uint64_t s = 0; s < h.table_.size(); ++s) {
    const std::uint64_t r = h.table_[s];
    if (r == 0) continue;
    if (h.find_slot(k.sh_record_key(s, r)) != s)
      bad("slot " + std::to_string(s) + ": a lookup of its key does not find it there (the Robin Hood order is "
          "broken, or the key is stored twice)");
  }
  return h;
}

SpatialHash::SpatialHash(SpatialHashConfig config, Extent table, bool) : config_(config) {
  config_.validate();
  fold_ = FoldedDomain(config_.domain);
  reset(table);
}

void SpatialHash::reset(Extent table) {
  check_fits_in_memory("spatial hash: a table of " + table.str() + " slots", memory_for(config_, table));
  const std::uint32_t amax = (1u << config_.age_bits) - 1u;
  extent_ = table;
  quotient_x_ = ceil_div(fold_.folded().x, table.x);
  offsets_.emplace(OffsetSequence::make(config_.offsets, table, amax, config_.seed));
  table_.assign(table.area(), 0);
  cells_x_ = ceil_div(table.x, config_.block);
  params_.emplace(config_.age_bits, table, quotient_x_, config_.block, config_.iter_limit, config_.miss_filter_bits);
  max_age_.assign(std::uint64_t{cells_x_} * ceil_div(table.y, config_.block), 0);
  filter_.assign(params_->filter_words, 0);
  live_ = tombstones_ = 0;
}

void SpatialHash::fill_filter() {
  std::fill(filter_.begin(), filter_.end(), 0);
  if (filter_.empty()) return;
  SpatialHashKernel<false> k = reader();
  for (std::uint64_t s = 0; s < table_.size(); ++s) {
    const std::uint64_t r = table_[s];
    if (r == 0) continue;
    const glm::uvec2 pos = k.sh_position(k.sh_record_key(s, r));
    filter_[k.sh_filter_word(pos)] |= k.sh_filter_bits(pos, k.sh_quotient(r));
  }
}

void SpatialHash::set_miss_filter(std::uint32_t bits) {
  SpatialHashConfig c = config_;
  c.miss_filter_bits = bits;
  c.validate();
  config_.miss_filter_bits = bits;
  params_.emplace(config_.age_bits, extent_, quotient_x_, config_.block, config_.iter_limit, bits);
  filter_.assign(params_->filter_words, 0);
  filter_.shrink_to_fit();
  fill_filter();
}

void SpatialHash::set_threads(std::uint32_t threads) {
  if (threads > kMaxThreads)
    throw std::invalid_argument("spatial hash: threads " + std::to_string(threads) + " outside 0.." +
                                std::to_string(kMaxThreads));
  config_.threads = threads;
}

std::uint32_t SpatialHash::threads() const {
  return config_.threads == 0 ? default_concurrency() : config_.threads;
}

SpatialHashKernel<false> SpatialHash::reader() const {
  return SpatialHashKernel<false>(*params_, offsets_->values().data(), const_cast<std::uint64_t*>(table_.data()),
                                  const_cast<std::uint32_t*>(max_age_.data()), const_cast<std::uint32_t*>(filter_.data()));
}

SpatialHashView::SpatialHashView(const SpatialHash& t)
    : kernel_(t.kernel_params(), t.offsets().values().data(), const_cast<std::uint64_t*>(t.table().data()),
              const_cast<std::uint32_t*>(t.max_age().data()), const_cast<std::uint32_t*>(t.filter().data())),
      fold_(t.domain()),
      slots_(t.table().data()),
      max_age_(t.max_age().data()),
      filter_(t.filter().empty() ? nullptr : t.filter().data()),
      complement_(t.config().rule == DuplicateRule::Min) {}

void SpatialHash::check_key(glm::uvec3 key, std::size_t index, bool batch) const {
  if (fold_.contains(key)) return;
  std::string where = batch ? "key " + std::to_string(index) + " " : "key ";
  throw std::invalid_argument("spatial hash: " + where + key_text(key) + " is outside the domain " +
                              config_.domain.str());
}

std::uint32_t SpatialHash::encode(std::uint32_t value) const {
  return config_.rule == DuplicateRule::Min ? ~value : value;
}
std::uint32_t SpatialHash::decode(std::uint32_t word) const {
  return config_.rule == DuplicateRule::Min ? ~word : word;
}

std::vector<SpatialHash::Pending> SpatialHash::insert_pass(std::span<const Pending> records, InsertReport& report) {
  const SpatialKernelParams& p = *params_;
  const std::uint32_t n = records.size() < kParallelMin ? 1u : std::min<std::uint32_t>(threads(), 256u);
  std::vector<InsertReport> reports(n);
  std::vector<std::vector<Pending>> dropped(n);
  const auto run = [&]<bool Concurrent>(std::uint32_t t) {
    SpatialHashKernel<Concurrent> k(p, offsets_->values().data(), table_.data(), max_age_.data(), filter_.data());
    InsertReport& r = reports[t];
    const std::size_t lo = records.size() * t / n, hi = records.size() * (t + 1) / n;
    for (std::size_t i = lo; i < hi; ++i) {
      auto c = k.sh_carry_begin(records[i].key, 1u, records[i].word);
      switch (k.sh_insert_run(c)) {
        case HABUFFER_SH_STORED: ++r.stored; break;
        case HABUFFER_SH_REVIVED: ++r.stored; ++r.tombstones_dropped; break;
        case HABUFFER_SH_STORED_TOMBSTONE_DROPPED: ++r.stored; ++r.tombstones_dropped; break;
        case HABUFFER_SH_DUPLICATE: ++r.duplicates; break;
        case HABUFFER_SH_FAILED_AGE:
          ++r.failed_age;
          dropped[t].push_back({k.sh_carry_key(c), k.sh_value(c.r)});
          break;
        default:
          ++r.failed_iter;
          dropped[t].push_back({k.sh_carry_key(c), k.sh_value(c.r)});
          break;
      }
    }
  };
  if (n == 1) {
    run.template operator()<false>(0);
  } else {
    run_with_threads(n, [&] { fork_join(n, [&](std::uint32_t t) { run.template operator()<true>(t); }); });
  }
  std::vector<Pending> out;
  for (std::uint32_t t = 0; t < n; ++t) {
    report += reports[t];
    live_ += reports[t].stored;
    tombstones_ -= reports[t].tombstones_dropped;
    out.insert(out.end(), dropped[t].begin(), dropped[t].end());
  }
  report.calls += records.size();
  return out;
}

std::vector<SpatialHash::Pending> SpatialHash::live_records() const {
  std::vector<Pending> out;
  out.reserve(live_);
  SpatialHashKernel<false> k = reader();
  for (std::uint64_t s = 0; s < table_.size(); ++s) {
    const std::uint64_t r = table_[s];
    if (r == 0 || k.sh_live(r) == 0u) continue;
    out.push_back({k.sh_record_key(s, r), k.sh_value(r)});
  }
  return out;
}

void SpatialHash::rebuild(Extent table, std::vector<Pending> extra, InsertReport& report) {
  std::vector<Pending> records = live_records();
  records.insert(records.end(), extra.begin(), extra.end());
  for (std::uint32_t growth = 0;; ++growth) {
    reset(table);
    ++report.rehashes;
    InsertReport scratch;  // re-insertions are not the caller's inserts
    std::vector<Pending> dropped = insert_pass(records, scratch);
    if (dropped.empty()) return;
    if (!config_.lossless) {
      report.lost += dropped.size();
      return;
    }
    if (growth >= config_.max_growths || table == fold_.folded()) {
      report.lost += dropped.size();
      totals_ += report;
      throw std::runtime_error("spatial hash: " + std::to_string(dropped.size()) + " keys still fail after " +
                               std::to_string(growth) + " growths (table " + extent_.str() + ", " +
                               std::to_string(config_.age_bits) + " age bits); the table holds every other key");
    }
    table = grown(table, fold_.folded());
  }
}

void SpatialHash::grow_if_needed(std::uint64_t incoming, InsertReport& report) {
  if (!config_.adaptive) return;
  const double after = static_cast<double>(live_ + tombstones_ + incoming);
  if (after <= config_.grow_at * static_cast<double>(table_.size())) return;
  Extent t = table_for(fold_, config_.age_bits, live_ + incoming, config_.target_load);
  if (static_cast<double>(t.area()) < 1.25 * static_cast<double>(table_.size())) t = grown(extent_, fold_.folded());
  rebuild(t, {}, report);
}

void SpatialHash::insert_records(std::vector<Pending> records, InsertReport& report) {
  grow_if_needed(records.size(), report);
  std::vector<Pending> dropped = insert_pass(records, report);
  if (dropped.empty()) return;
  if (!config_.lossless) {
    report.lost += dropped.size();
    return;
  }
  rebuild(grown(extent_, fold_.folded()), std::move(dropped), report);
}

InsertReport SpatialHash::insert(std::span<const glm::uvec3> keys, std::span<const std::uint32_t> values) {
  if (!values.empty() && values.size() != keys.size())
    throw std::invalid_argument("spatial hash: " + std::to_string(keys.size()) + " keys but " +
                                std::to_string(values.size()) + " values");
  if (keys.size() > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("spatial hash: a batch of " + std::to_string(keys.size()) +
                                " keys; insert at most 2^32 - 1 at once");
  for (std::size_t i = 0; i < keys.size(); ++i) check_key(keys[i], i, keys.size() > 1);
  InsertReport report;
  const auto value_of = [&](std::size_t i) { return values.empty() ? 0u : values[i]; };
  const bool ordered = config_.rule == DuplicateRule::First || config_.rule == DuplicateRule::Last;
  if (!ordered) {
    std::vector<Pending> records(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) records[i] = {fold_.fold(keys[i]), encode(value_of(i))};
    insert_records(std::move(records), report);
    totals_ += report;
    return report;
  }
  // First / Last: the batch's keys once each, the one of the largest
  // priority (Last: its index; First: the index's complement) kept by a
  // table of the batch, then merged with this table's keys.
  const bool last = config_.rule == DuplicateRule::Last;
  std::vector<Pending> distinct;
  if (keys.size() == 1) {
    distinct.push_back({fold_.fold(keys[0]), value_of(0)});
  } else {
    SpatialHashConfig c = config_;
    c.rule = DuplicateRule::Max;
    c.adaptive = true;
    c.lossless = true;
    SpatialHash batch(c, keys.size());
    std::vector<Pending> records(keys.size());
    for (std::size_t i = 0; i < keys.size(); ++i) {
      const auto index = static_cast<std::uint32_t>(i);
      records[i] = {fold_.fold(keys[i]), last ? index : ~index};
    }
    InsertReport inner;
    batch.insert_records(std::move(records), inner);
    report.duplicates += inner.duplicates;
    distinct = batch.live_records();
    for (Pending& d : distinct) d.word = value_of(last ? d.word : ~d.word);
  }
  std::vector<Pending> absent;
  std::uint64_t merged = 0;
  for (const Pending& d : distinct) {
    const std::uint64_t s = find_slot(d.key);
    if (s == kNoSlot || (table_[s] >> 32 & 1u) == 0u) {
      absent.push_back(d);
      continue;
    }
    ++merged;
    if (last) table_[s] = (table_[s] & 0xFFFFFFFF00000000ull) | d.word;
  }
  report.duplicates += merged;
  report.calls += keys.size() - absent.size();  // insert_records counts the absent ones' calls
  insert_records(std::move(absent), report);
  totals_ += report;
  return report;
}

InsertReport SpatialHash::insert(glm::uvec3 key, std::uint32_t value) {
  return insert(std::span<const glm::uvec3>(&key, 1), std::span<const std::uint32_t>(&value, 1));
}

std::uint64_t SpatialHash::find_slot(glm::uvec2 folded) const {
  SpatialHashKernel<false> k = reader();
  std::uint32_t probes = 0;
  return k.sh_find_slot(folded, probes);
}

std::optional<std::uint32_t> SpatialHash::find(glm::uvec3 key) const {
  check_key(key, 0, false);
  return view().find(key);
}

std::uint32_t SpatialHash::probes(glm::uvec3 key) const {
  check_key(key, 0, false);
  SpatialHashKernel<false> k = reader();
  std::uint32_t probes = 0;
  (void)k.sh_find_slot(fold_.fold(key), probes);
  return probes;
}

std::uint64_t SpatialHash::find(std::span<const glm::uvec3> keys, std::span<std::uint32_t> values,
                                std::span<std::uint8_t> found) const {
  if (values.size() != keys.size() || found.size() != keys.size())
    throw std::invalid_argument("spatial hash: find of " + std::to_string(keys.size()) + " keys into " +
                                std::to_string(values.size()) + " values and " + std::to_string(found.size()) +
                                " flags");
  for (std::size_t i = 0; i < keys.size(); ++i) check_key(keys[i], i, true);
  const std::uint32_t n = keys.size() < kParallelMin ? 1u : std::min<std::uint32_t>(threads(), 256u);
  std::vector<std::uint64_t> hits(n, 0);
  const auto run = [&](std::uint32_t t) {
    const SpatialHashView v = view();
    const std::size_t lo = keys.size() * t / n, hi = keys.size() * (t + 1) / n;
    std::uint64_t count = 0;
    constexpr std::size_t kAhead = 12;  // keys whose first probe is in flight
    for (std::size_t i = lo; i < std::min(hi, lo + kAhead); ++i) v.prefetch(keys[i]);
    for (std::size_t i = lo; i < hi; ++i) {
      if (i + kAhead < hi) v.prefetch(keys[i + kAhead]);
      const std::optional<std::uint32_t> got = v.find(keys[i]);
      values[i] = got.value_or(0u);
      found[i] = got ? 1u : 0u;
      count += got.has_value();
    }
    hits[t] = count;
  };
  if (n == 1) run(0);
  else run_with_threads(n, [&] { fork_join(n, run); });
  std::uint64_t total = 0;
  for (const std::uint64_t h : hits) total += h;
  return total;
}

bool SpatialHash::erase(glm::uvec3 key) {
  check_key(key, 0, false);
  const std::uint64_t s = find_slot(fold_.fold(key));
  if (s == kNoSlot || (table_[s] >> 32 & 1u) == 0u) return false;
  table_[s] &= 0xFFFFFFFE00000000ull;  // the tombstone: key bits, live 0, value 0
  --live_;
  ++tombstones_;
  shrink_if_needed();
  return true;
}

std::uint64_t SpatialHash::erase(std::span<const glm::uvec3> keys) {
  for (std::size_t i = 0; i < keys.size(); ++i) check_key(keys[i], i, true);
  std::uint64_t erased = 0;
  for (const glm::uvec3 key : keys) {
    const std::uint64_t s = find_slot(fold_.fold(key));
    if (s == kNoSlot || (table_[s] >> 32 & 1u) == 0u) continue;
    table_[s] &= 0xFFFFFFFE00000000ull;
    --live_;
    ++tombstones_;
    ++erased;
  }
  shrink_if_needed();
  return erased;
}

void SpatialHash::shrink_if_needed() {
  if (!config_.adaptive) return;
  const double slots = static_cast<double>(table_.size());
  InsertReport report;
  if (static_cast<double>(live_) < config_.shrink_at * slots && table_.size() > 1) {
    const Extent t = table_for(fold_, config_.age_bits, live_, config_.target_load);
    if (t.area() < table_.size()) {
      rebuild(t, {}, report);
      return;
    }
  }
  // Tombstones past a quarter of the table: compact, so loads stay honest.
  if (static_cast<double>(tombstones_) > 0.25 * slots) rebuild(extent_, {}, report);
}

void SpatialHash::compact() {
  InsertReport report;
  rebuild(extent_, {}, report);
}

void SpatialHash::rehash(Extent table) {
  if (table.x == 0 || table.y == 0 || table.x > fold_.folded().x || table.y > fold_.folded().y)
    throw std::invalid_argument("spatial hash: table " + table.str() + " is not within the folded domain " +
                                fold_.folded().str());
  if (!quotients_fit(fold_.folded(), table, config_.age_bits))
    throw std::invalid_argument("spatial hash: table " + table.str() + " leaves quotients of more than " +
                                std::to_string(31u - config_.age_bits) + " bits for the domain " +
                                config_.domain.str());
  InsertReport report;
  rebuild(table, {}, report);
}

void SpatialHash::reserve(std::uint64_t keys, double load) {
  InsertReport report;
  rebuild(table_for(fold_, config_.age_bits, keys, load), {}, report);
}

void SpatialHash::clear() {
  std::fill(table_.begin(), table_.end(), 0);
  std::fill(max_age_.begin(), max_age_.end(), 0);
  std::fill(filter_.begin(), filter_.end(), 0);
  live_ = tombstones_ = 0;
}

std::optional<Entry> SpatialHash::entry_at(SpatialHashKernel<false>& k, std::uint64_t s) const {
  const std::uint64_t r = table_[s];
  if (r == 0 || k.sh_live(r) == 0u) return std::nullopt;
  return Entry{fold_.unfold(k.sh_record_key(s, r)), decode(k.sh_value(r))};
}

std::vector<Entry> SpatialHash::entries() const {
  std::vector<Entry> out;
  out.reserve(live_);
  for_each([&](const Entry& e) { out.push_back(e); });
  return out;
}

std::vector<Entry> SpatialHash::neighbourhood(glm::uvec3 centre, std::uint32_t radius) const {
  check_key(centre, 0, false);
  if (radius > 64) throw std::invalid_argument("spatial hash: neighbourhood radius " + std::to_string(radius) + " above 64");
  const Domain d = config_.domain;
  const auto lo = [&](std::uint32_t c) { return c >= radius ? c - radius : 0u; };
  const auto hi = [&](std::uint32_t c, std::uint32_t side) { return std::min<std::uint64_t>(side - 1u, std::uint64_t{c} + radius); };
  std::vector<Entry> out;
  for (std::uint64_t z = lo(centre.z); z <= hi(centre.z, d.z); ++z)
    for (std::uint64_t y = lo(centre.y); y <= hi(centre.y, d.y); ++y)
      for (std::uint64_t x = lo(centre.x); x <= hi(centre.x, d.x); ++x) {
        const glm::uvec3 k(static_cast<std::uint32_t>(x), static_cast<std::uint32_t>(y), static_cast<std::uint32_t>(z));
        if (const std::optional<std::uint32_t> v = find(k)) out.push_back({k, *v});
      }
  return out;
}

double SpatialHash::load() const {
  return static_cast<double>(live_ + tombstones_) / static_cast<double>(table_.size());
}

std::uint64_t SpatialHash::memory_bytes() const {
  return table_.size() * sizeof(std::uint64_t) + (max_age_.size() + filter_.size()) * sizeof(std::uint32_t) +
         offsets_->size() * sizeof(glm::uvec2);
}

SpatialHashStats SpatialHash::stats() const {
  SpatialHashStats s;
  s.table = extent_;
  s.slots = table_.size();
  s.keys = live_;
  s.tombstones = tombstones_;
  s.load = load();
  s.ages.assign((std::size_t{1} << config_.age_bits), 0);
  double sum = 0.0;
  for (const std::uint64_t r : table_) {
    if (r == 0) continue;
    const auto age = static_cast<std::uint32_t>(r >> (64u - config_.age_bits));
    s.max_age = std::max(s.max_age, age);
    if ((r >> 32 & 1u) == 0u) continue;
    ++s.ages[age];
    sum += age;
  }
  s.mean_age = live_ == 0 ? 0.0 : sum / static_cast<double>(live_);
  s.quotient_bits = bits_for(std::uint64_t{quotient_x_} * ceil_div(fold_.folded().y, extent_.y));
  s.memory_bytes = memory_bytes();
  s.bytes_per_key = live_ == 0 ? 0.0 : static_cast<double>(s.memory_bytes) / static_cast<double>(live_);
  return s;
}

}  // namespace habuffer::spatial
