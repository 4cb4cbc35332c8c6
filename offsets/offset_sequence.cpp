#include "habuffer/offset_sequence.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <unordered_set>

#include "habuffer/random.h"

namespace habuffer {
namespace {

std::uint64_t slot_of(glm::uvec2 o, Extent table) { return o.x + std::uint64_t{o.y} * table.x; }

std::uint32_t distinct_needed(Extent table, std::uint32_t count) {
  return static_cast<std::uint32_t>(std::min<std::uint64_t>(count, table.area()));
}

void check_count(std::uint32_t count, Extent table) {
  if (count == 0) throw std::invalid_argument("offset count must be positive");
  if (table.area() == 0) throw std::invalid_argument("offsets: table " + table.str() + " has no slots");
}

}  // namespace

OffsetSequence::OffsetSequence(Extent table, OffsetGenerator gen, std::vector<glm::uvec2> distinct,
                               std::uint32_t count)
    : table_(table), generator_(gen) {
  values_.reserve(count);
  for (std::uint32_t i = 0; i < count; ++i) values_.push_back(distinct[i % distinct.size()]);
}

OffsetSequence OffsetSequence::random(Extent table, std::uint32_t count, std::uint64_t seed) {
  check_count(count, table);
  SplitMix64 rng(seed ^ 0x6A09E667F3BCC908ull);
  const std::uint32_t n = distinct_needed(table, count);
  std::vector<glm::uvec2> picked;
  picked.reserve(n);
  if (std::uint64_t{n} * 2 >= table.area()) {
    // Small table: a seeded partial Fisher-Yates over all slots.
    std::vector<std::uint32_t> slots(table.area());
    for (std::uint32_t i = 0; i < slots.size(); ++i) slots[i] = i;
    for (std::uint32_t i = 0; i < n; ++i) {
      auto j = i + static_cast<std::uint32_t>(rng.below(slots.size() - i));
      std::swap(slots[i], slots[j]);
      picked.emplace_back(slots[i] % table.x, slots[i] / table.x);
    }
  } else {
    std::unordered_set<std::uint64_t> used;
    while (picked.size() < n) {
      glm::uvec2 o(static_cast<std::uint32_t>(rng.below(table.x)), static_cast<std::uint32_t>(rng.below(table.y)));
      if (used.insert(slot_of(o, table)).second) picked.push_back(o);
    }
  }
  return OffsetSequence(table, OffsetGenerator::Random, std::move(picked), count);
}

OffsetSequence OffsetSequence::from_list(Extent table, std::uint32_t count, std::span<const glm::uvec2> rows) {
  check_count(count, table);
  const std::uint32_t n = distinct_needed(table, count);
  if (rows.size() < n)
    throw std::invalid_argument("offsets: " + std::to_string(rows.size()) + " rows given, " + std::to_string(n) +
                                " needed (one per age 1.." + std::to_string(n) + ") for table " + table.str());
  std::unordered_set<std::uint64_t> used;
  for (std::size_t i = 0; i < std::min<std::size_t>(rows.size(), count); ++i) {
    const auto o = rows[i];
    const std::string where = "offsets row " + std::to_string(i + 1) + " (age " + std::to_string(i + 1) + ")";
    if (o.x >= table.x || o.y >= table.y)
      throw std::invalid_argument(where + ": offset (" + std::to_string(o.x) + "," + std::to_string(o.y) +
                                  ") lies outside table " + table.str());
    if (i < n && !used.insert(slot_of(o, table)).second)
      throw std::invalid_argument(where + ": duplicate offset (" + std::to_string(o.x) + "," + std::to_string(o.y) +
                                  "); offsets must be pairwise distinct");
    if (i >= n && o != rows[i % n])
      throw std::invalid_argument(where + ": table " + table.str() + " has only " + std::to_string(n) +
                                  " slots, so offsets must repeat cyclically (row i = row i mod " +
                                  std::to_string(n) + ")");
  }
  return OffsetSequence(table, OffsetGenerator::List, std::vector<glm::uvec2>(rows.begin(), rows.begin() + n), count);
}

OffsetSequence OffsetSequence::make(OffsetGenerator gen, Extent table, std::uint32_t count, std::uint64_t seed) {
  switch (gen) {
    case OffsetGenerator::Random: return random(table, count, seed);
    case OffsetGenerator::Farthest: return farthest(table, count, seed);
    case OffsetGenerator::List: break;
  }
  throw std::invalid_argument("offsets: a list of offsets cannot be generated, it must be given");
}

std::uint64_t toroidal_distance2(glm::uvec2 a, glm::uvec2 b, Extent table) {
  auto axis = [](std::uint32_t u, std::uint32_t v, std::uint32_t size) {
    std::uint64_t d = u > v ? u - v : v - u;
    return std::min<std::uint64_t>(d, size - d);
  };
  const auto dx = axis(a.x, b.x, table.x), dy = axis(a.y, b.y, table.y);
  return dx * dx + dy * dy;
}

std::vector<double> min_pairwise_distances(std::span<const glm::uvec2> offsets, Extent table) {
  std::vector<double> result;
  std::uint64_t best = UINT64_MAX;
  for (std::size_t k = 1; k < offsets.size(); ++k) {
    for (std::size_t j = 0; j < k; ++j) best = std::min(best, toroidal_distance2(offsets[k], offsets[j], table));
    result.push_back(std::sqrt(static_cast<double>(best)));
  }
  return result;
}

std::optional<OffsetGenerator> parse_offset_generator(std::string_view name) {
  if (name == "random") return OffsetGenerator::Random;
  if (name == "farthest") return OffsetGenerator::Farthest;
  return std::nullopt;
}

std::string to_string(OffsetGenerator gen) {
  switch (gen) {
    case OffsetGenerator::Random: return "random";
    case OffsetGenerator::Farthest: return "farthest";
    case OffsetGenerator::List: return "list";
  }
  return "?";
}

}  // namespace habuffer
