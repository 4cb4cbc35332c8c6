#include "habuffer/spatial_hash_file.h"

#include <bit>
#include <cstring>
#include <stdexcept>

#include "habuffer/atomic_file.h"
#include "habuffer/bounded_read.h"
#include "habuffer/little_endian.h"
#include "habuffer/csv.h"
#include "habuffer/printable.h"

namespace habuffer::spatial {
namespace {

constexpr char kMagic[8] = {'H', 'A', 'S', 'P', 'A', 'T', 'L', '1'};
constexpr std::size_t kHeader = 8 + 10 * 4 + 8;

// The largest table file: SpatialHash::kMaxSlots slots and as many max-age
// cells (block 1). Anything longer is not a table, whatever its header says.
constexpr std::uint64_t kMaxTableBytes = kHeader + SpatialHash::kMaxSlots * (8 + 4);

}  // namespace

KeyFile read_keys_csv(const std::string& path) {
  CsvReader csv(path);
  KeyFile f;
  // Read once, from the reader itself: a pipe gives its header only once.
  const std::size_t header = csv.expect_header_among({{"x", "y"}, {"x", "y", "z"}, {"x", "y", "value"}, {"x", "y", "z", "value"}});
  f.three_d = header == 1 || header == 3;
  const bool values = header >= 2;
  std::vector<std::string_view> fields;
  while (csv.next(fields)) {
    glm::uvec3 k(csv.u32(fields[0], "x"), csv.u32(fields[1], "y"), 0u);
    if (f.three_d) k.z = csv.u32(fields[2], "z");
    f.keys.push_back(k);
    if (values) f.values.push_back(csv.u32_dec_or_hex(fields.back(), "value"));
  }
  return f;
}

Domain domain_of(const std::vector<glm::uvec3>& keys) {
  Domain d{1, 1, 1};
  for (const glm::uvec3 k : keys) {
    if (k.x == 0xFFFFFFFFu || k.y == 0xFFFFFFFFu || k.z == 0xFFFFFFFFu)
      throw DataError("key (" + std::to_string(k.x) + ", " + std::to_string(k.y) + ", " + std::to_string(k.z) +
                      ") has a coordinate of 2^32 - 1: a domain holding it would need 2^32 points on that axis");
    d.x = std::max(d.x, k.x + 1);
    d.y = std::max(d.y, k.y + 1);
    d.z = std::max(d.z, k.z + 1);
  }
  return d;
}

void save_spatial_hash(const std::string& path, const SpatialHash& t) {
  const SpatialHashConfig& c = t.config();
  std::string bytes(kMagic, sizeof kMagic);
  for (const std::uint32_t v :
       {c.domain.x, c.domain.y, c.domain.z, static_cast<std::uint32_t>(c.rule), c.age_bits, c.block,
        static_cast<std::uint32_t>(c.offsets), c.iter_limit, t.table_extent().x, t.table_extent().y})
    put_le<std::uint32_t>(bytes, v);
  put_le<std::uint64_t>(bytes, c.seed);
  bytes.reserve(bytes.size() + t.table().size() * 8 + t.max_age().size() * 4);
  for (const std::uint64_t w : t.table()) put_le<std::uint64_t>(bytes, w);
  for (const std::uint32_t m : t.max_age()) put_le<std::uint32_t>(bytes, m);
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
}

SpatialHash load_spatial_hash(const std::string& path) {
  return parse_spatial_hash(read_file_bounded(path, "spatial hash table", kMaxTableBytes), printable(path));
}

SpatialHash parse_spatial_hash(const std::string& bytes, const std::string& path) {
  if (bytes.size() < kHeader || bytes.compare(0, 8, kMagic, 8) != 0)
    throw DataError(path + ": not a spatial hash table (no HASPATL1 header)");
  SpatialHashConfig c;
  c.domain = {take_le<std::uint32_t>(bytes, 8), take_le<std::uint32_t>(bytes, 12), take_le<std::uint32_t>(bytes, 16)};
  const std::uint32_t rule = take_le<std::uint32_t>(bytes, 20), generator = take_le<std::uint32_t>(bytes, 32);
  if (rule > 3) throw DataError(path + ": duplicate rule " + std::to_string(rule) + " is not 0..3");
  if (generator > 1) throw DataError(path + ": offsets generator " + std::to_string(generator) + " is not 0..1");
  c.rule = static_cast<DuplicateRule>(rule);
  c.age_bits = take_le<std::uint32_t>(bytes, 24);
  c.block = take_le<std::uint32_t>(bytes, 28);
  c.offsets = static_cast<OffsetGenerator>(generator);
  c.iter_limit = take_le<std::uint32_t>(bytes, 36);
  const Extent table{take_le<std::uint32_t>(bytes, 40), take_le<std::uint32_t>(bytes, 44)};
  c.seed = take_le<std::uint64_t>(bytes, 48);
  try {
    c.validate();
    if (table.x == 0 || table.y == 0 || c.block == 0)
      throw std::invalid_argument("table " + table.str() + " has a zero side");
    if (table.area() > bytes.size() / 8)
      throw std::invalid_argument("a table of " + table.str() + " in " + std::to_string(bytes.size()) + " bytes");
    const std::uint64_t cells = std::uint64_t{(table.x + c.block - 1) / c.block} * ((table.y + c.block - 1) / c.block);
    const std::uint64_t want = kHeader + table.area() * 8 + cells * 4;
    if (bytes.size() != want)
      throw std::invalid_argument(std::to_string(bytes.size()) + " bytes, a table of " + table.str() + " has " +
                                  std::to_string(want));
    std::vector<std::uint64_t> slots(table.area());
    std::memcpy(slots.data(), bytes.data() + kHeader, slots.size() * 8);
    std::vector<std::uint32_t> max_age(cells);
    std::memcpy(max_age.data(), bytes.data() + kHeader + slots.size() * 8, cells * 4);
    return SpatialHash::restore(c, table, std::move(slots), std::move(max_age));
  } catch (const std::invalid_argument& e) {
    throw DataError(path + ": " + e.what());
  }
}

}  // namespace habuffer::spatial
