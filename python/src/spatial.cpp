// The spatial hash (habuffer.SpatialHash): build from a (N, 2|3) uint32 key
// array and optional uint32 values; find and contains on arrays of keys,
// concurrently with the GIL released. SpatialHash orders nothing between
// calls (its threads are a call's own), so the binding does: finds and
// reads share a lock, insert and erase (which may rehash, moving the
// storage) hold it alone. table() and max_age() are therefore copies.
#include <pybind11/stl.h>

#include <mutex>
#include <shared_mutex>

#include "arrays.h"
#include "bindings.h"
#include "config.h"
#include "habuffer/spatial/spatial_hash.h"

namespace habuffer::python {
namespace {

using namespace pybind11::literals;
using spatial::SpatialHash;
using spatial::SpatialHashConfig;

// The table and the lock that orders Python's calls on it.
class LockedHash {
 public:
  LockedHash(const SpatialHashConfig& c, std::uint64_t capacity) : table_(c, capacity) {}

  // f(table) with the GIL released, beside other readers (the lock taken
  // after the GIL is released and dropped before it is taken back).
  template <class F>
  auto read(F f) const {
    py::gil_scoped_release release;
    const std::shared_lock lock(mutex_);
    return f(static_cast<const SpatialHash&>(table_));
  }
  // f(table) with the GIL released, alone.
  template <class F>
  auto change(F f) {
    py::gil_scoped_release release;
    const std::unique_lock lock(mutex_);
    return f(table_);
  }

 private:
  SpatialHash table_;
  mutable std::shared_mutex mutex_;
};

std::vector<glm::uvec3> keys_from(py::handle obj) {
  auto a = checked_array<std::uint32_t>(obj, "keys", 2);
  const py::ssize_t d = a.shape(1);
  if (d != 2 && d != 3) throw py::value_error("keys: expected shape (N, 2) or (N, 3), got " + shape_text(a));
  const auto r = a.unchecked<2>();
  std::vector<glm::uvec3> keys(static_cast<std::size_t>(a.shape(0)));
  for (py::ssize_t i = 0; i < a.shape(0); ++i)
    keys[static_cast<std::size_t>(i)] = glm::uvec3(r(i, 0), r(i, 1), d == 3 ? r(i, 2) : 0u);
  return keys;
}

std::vector<std::uint32_t> values_from(py::handle obj, std::size_t n) {
  if (obj.is_none()) return {};
  const auto a = checked_array<std::uint32_t>(obj, "values", 1);
  if (static_cast<std::size_t>(a.shape(0)) != n)
    throw py::value_error("values: " + std::to_string(a.shape(0)) + " values for " + std::to_string(n) + " keys");
  const auto r = a.unchecked<1>();
  std::vector<std::uint32_t> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = r(static_cast<py::ssize_t>(i));
  return v;
}

py::dict report_dict(const spatial::InsertReport& r) {
  return py::dict("calls"_a = r.calls, "stored"_a = r.stored, "duplicates"_a = r.duplicates,
                  "failed_age"_a = r.failed_age, "failed_iter"_a = r.failed_iter, "lost"_a = r.lost,
                  "rehashes"_a = r.rehashes);
}

// The batched find of keys (N, 2|3): each key's value (0 where absent) and whether it is there.
struct Lookup {
  std::vector<std::uint32_t> values;
  std::vector<std::uint8_t> found;
};

Lookup look_up(const LockedHash& h, py::handle keys_obj) {
  const std::vector<glm::uvec3> keys = keys_from(keys_obj);
  Lookup r{std::vector<std::uint32_t>(keys.size()), std::vector<std::uint8_t>(keys.size())};
  h.read([&](const SpatialHash& t) { return t.find(keys, r.values, r.found); });
  return r;
}

py::array_t<bool> mask_of(const std::vector<std::uint8_t>& found) {
  py::array_t<bool> mask(static_cast<py::ssize_t>(found.size()));
  for (std::size_t i = 0; i < found.size(); ++i) mask.mutable_at(static_cast<py::ssize_t>(i)) = found[i] != 0;
  return mask;
}


std::unique_ptr<LockedHash> make_hash(py::handle domain, const IntArg& capacity_arg, const std::string& rule,
                                      const IntArg& age_bits, double load, bool adaptive, const IntArg& seed,
                                      const std::string& offsets, const IntArg& threads,
                                      const IntArg& miss_filter_bits) {
  SpatialHashConfig c;
  c.domain = domain_arg(domain);
  const std::uint64_t capacity = uint_arg(capacity_arg, "capacity", 0, UINT64_MAX);
  // A table that never resizes, sized for no key, would hold one slot and
  // grow only through lossless growth's 25 % steps, failing after it.
  if (!adaptive && capacity == 0)
    throw py::value_error("capacity: a table with adaptive=False keeps the size it is made with: give capacity=N "
                          "(the keys it will hold), or leave adaptive=True");
  const std::optional<spatial::DuplicateRule> r = spatial::parse_duplicate_rule(rule);
  if (!r) throw py::value_error("rule: '" + rule + "' is not max, min, first or last");
  c.rule = *r;
  c.age_bits = u32_arg(age_bits, "age_bits", HABUFFER_SH_MIN_AGE_BITS, HABUFFER_SH_MAX_AGE_BITS);
  c.target_load = load;
  c.adaptive = adaptive;
  if (adaptive && c.target_load > c.grow_at) c.grow_at = c.target_load;  // as habuffer hash build
  c.seed = seed_arg(seed);
  c.offsets = offsets_arg(offsets);
  c.threads = threads_arg(threads);
  c.miss_filter_bits = u32_arg(miss_filter_bits, "miss_filter_bits", 0, 16);
  if (c.miss_filter_bits % 8 != 0)
    throw py::value_error("miss_filter_bits: " + std::to_string(c.miss_filter_bits) + " is not 0, 8 or 16");
  return std::make_unique<LockedHash>(c, capacity);
}

py::dict insert_keys(LockedHash& h, py::handle keys_obj, py::handle values_obj) {
  const std::vector<glm::uvec3> keys = keys_from(keys_obj);
  const std::vector<std::uint32_t> values = values_from(values_obj, keys.size());
  return report_dict(h.change([&](SpatialHash& t) { return t.insert(keys, values); }));
}

py::dict table_stats(const LockedHash& h) {
  const spatial::SpatialHashStats s = h.read([](const SpatialHash& t) { return t.stats(); });
  return py::dict("slots"_a = s.slots, "keys"_a = s.keys, "tombstones"_a = s.tombstones, "load"_a = s.load,
                  "max_age"_a = s.max_age, "mean_age"_a = s.mean_age,
                  "ages"_a = owned_array(std::vector<std::uint64_t>(s.ages)), "quotient_bits"_a = s.quotient_bits,
                  "memory_bytes"_a = s.memory_bytes, "bytes_per_key"_a = s.bytes_per_key);
}

py::array table_copy(const LockedHash& h) {
  Extent e;
  std::vector<std::uint64_t> slots = h.read([&](const SpatialHash& t) {
    e = t.table_extent();
    return std::vector<std::uint64_t>(t.table().begin(), t.table().end());
  });
  return owned_array(std::move(slots)).reshape({static_cast<py::ssize_t>(e.y), static_cast<py::ssize_t>(e.x)});
}

py::array max_age_copy(const LockedHash& h) {
  return owned_array(h.read([](const SpatialHash& t) {
    return std::vector<std::uint32_t>(t.max_age().begin(), t.max_age().end());
  }));
}

}  // namespace

void bind_spatial(py::module_& m) {
  py::class_<LockedHash>(m, "SpatialHash",
                         "The coherent hash as a spatial hash table of 2D or 3D integer keys with 32-bit values "
                         "(habuffer hash): Robin Hood placement along the HA-buffer's coherent probe sequence. Calls "
                         "from several Python threads are safe: finds overlap, inserts and erases run alone.")
      .def(py::init(&make_hash), py::arg("domain"), py::kw_only(), py::arg("capacity") = 0, py::arg("rule") = "last",
           py::arg("age_bits") = HABUFFER_SH_DEFAULT_AGE_BITS, py::arg("load") = 0.8, py::arg("adaptive") = true,
           py::arg("seed") = 1, py::arg("offsets") = "random", py::arg("threads") = 0,
           py::arg("miss_filter_bits") = HABUFFER_SH_DEFAULT_FILTER_BITS,
           "An empty table for keys of `domain` ((X, Y) or (X, Y, Z)), sized for `capacity` keys at `load`; "
           "`miss_filter_bits` (16, 8 or 0: none) per slot answer most absent keys in one load (hits pay one more "
           "load).")
      .def("insert", &insert_keys, py::arg("keys"), py::arg("values") = py::none(),
           "Inserts keys (N, 2|3) uint32 with values (N,) uint32 (None: a set); duplicates by the rule. Returns the "
           "call's report (dict).")
      .def(
          "find",
          [](const LockedHash& h, py::handle keys) {
            Lookup r = look_up(h, keys);
            return py::make_tuple(owned_array(std::move(r.values)), mask_of(r.found));
          },
          py::arg("keys"), "(values, found): each key's value (0 where absent) and a bool mask of the keys present.")
      .def(
          "contains", [](const LockedHash& h, py::handle keys) { return mask_of(look_up(h, keys).found); },
          py::arg("keys"), "A bool mask of the keys present.")
      .def(
          "erase",
          [](LockedHash& h, py::handle keys_obj) {
            const std::vector<glm::uvec3> keys = keys_from(keys_obj);
            return h.change([&](SpatialHash& t) { return t.erase(keys); });
          },
          py::arg("keys"), "Erases keys; returns how many were present.")
      .def("__len__", [](const LockedHash& h) { return h.read([](const SpatialHash& t) { return t.size(); }); })
      .def_property_readonly("load",
                             [](const LockedHash& h) { return h.read([](const SpatialHash& t) { return t.load(); }); })
      .def_property_readonly(
          "memory_bytes", [](const LockedHash& h) { return h.read([](const SpatialHash& t) { return t.memory_bytes(); }); })
      .def_property_readonly("table_extent",
                             [](const LockedHash& h) {
                               const Extent e = h.read([](const SpatialHash& t) { return t.table_extent(); });
                               return py::make_tuple(e.x, e.y);
                             })
      .def("stats", &table_stats, "The table's statistics (habuffer hash stats).")
      .def("table", &table_copy,
           "The slots as a (Hy, Hx) uint64 array: a copy, since an insert may rehash into new storage.")
      .def("max_age", &max_age_copy, "The max-age cells, row-major, as a uint32 array (a copy).");
}

}  // namespace habuffer::python
