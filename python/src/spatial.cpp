// The spatial hash (habuffer.SpatialHash): build from a (N, 2|3) uint32 key
// array and optional uint32 values; find and contains on arrays of keys,
// concurrently with the GIL released; the table and max-age cells as
// zero-copy read-only views.
#include <pybind11/stl.h>

#include "arrays.h"
#include "bindings.h"
#include "habuffer/spatial/spatial_hash.h"

namespace habuffer::python {
namespace {

using namespace pybind11::literals;
using spatial::SpatialHash;
using spatial::SpatialHashConfig;

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

// The batched find of keys (N, 2|3), with the GIL released.
struct Lookup {
  py::array_t<std::uint32_t> values;  // 0 where absent
  py::array_t<bool> found;
};

Lookup look_up(const SpatialHash& table, py::handle keys_obj) {
  const std::vector<glm::uvec3> keys = keys_from(keys_obj);
  std::vector<std::uint32_t> values(keys.size());
  std::vector<std::uint8_t> found(keys.size());
  {
    py::gil_scoped_release release;
    table.find(keys, values, found);
  }
  py::array_t<bool> mask(static_cast<py::ssize_t>(found.size()));
  for (std::size_t i = 0; i < found.size(); ++i) mask.mutable_at(static_cast<py::ssize_t>(i)) = found[i] != 0;
  return {owned_array(std::move(values)), mask};
}

spatial::Domain domain_arg(py::handle obj) {
  const auto d = obj.cast<std::vector<std::uint32_t>>();
  if (d.size() != 2 && d.size() != 3) throw py::value_error("domain: expected (X, Y) or (X, Y, Z)");
  return spatial::Domain{d[0], d[1], d.size() == 3 ? d[2] : 1u};
}

}  // namespace

void bind_spatial(py::module_& m) {
  py::class_<SpatialHash>(m, "SpatialHash",
                          "The coherent hash as a spatial hash table of 2D or 3D integer keys with 32-bit values "
                          "(habuffer hash): Robin Hood placement along the HA-buffer's coherent probe sequence.")
      .def(py::init([](py::handle domain, std::uint64_t capacity, const std::string& rule, std::uint32_t age_bits,
                       double load, bool adaptive, std::uint64_t seed, const std::string& offsets,
                       std::uint32_t threads) {
             SpatialHashConfig c;
             c.domain = domain_arg(domain);
             const std::optional<spatial::DuplicateRule> r = spatial::parse_duplicate_rule(rule);
             if (!r) throw py::value_error("rule: '" + rule + "' is not max, min, first or last");
             c.rule = *r;
             c.age_bits = age_bits;
             c.target_load = load;
             c.adaptive = adaptive;
             if (adaptive && c.target_load > c.grow_at) c.grow_at = c.target_load;  // as habuffer hash build
             c.seed = seed;
             if (offsets != "random" && offsets != "farthest") throw py::value_error("offsets: random or farthest");
             c.offsets = offsets == "random" ? OffsetGenerator::Random : OffsetGenerator::Farthest;
             c.threads = threads;
             return std::make_unique<SpatialHash>(c, capacity);
           }),
           py::arg("domain"), py::kw_only(), py::arg("capacity") = 0, py::arg("rule") = "last",
           py::arg("age_bits") = HABUFFER_SH_DEFAULT_AGE_BITS, py::arg("load") = 0.8, py::arg("adaptive") = true,
           py::arg("seed") = 1, py::arg("offsets") = "random", py::arg("threads") = 0,
           "An empty table for keys of `domain` ((X, Y) or (X, Y, Z)), sized for `capacity` keys at `load`.")
      .def(
          "insert",
          [](SpatialHash& self, py::handle keys_obj, py::handle values_obj) {
            const std::vector<glm::uvec3> keys = keys_from(keys_obj);
            const std::vector<std::uint32_t> values = values_from(values_obj, keys.size());
            spatial::InsertReport r;
            {
              py::gil_scoped_release release;
              r = self.insert(keys, values);
            }
            return report_dict(r);
          },
          py::arg("keys"), py::arg("values") = py::none(),
          "Inserts keys (N, 2|3) uint32 with values (N,) uint32 (None: a set); duplicates by the rule. Returns the "
          "call's report (dict).")
      .def(
          "find",
          [](const SpatialHash& self, py::handle keys) {
            const Lookup r = look_up(self, keys);
            return py::make_tuple(r.values, r.found);
          },
          py::arg("keys"), "(values, found): each key's value (0 where absent) and a bool mask of the keys present.")
      .def(
          "contains", [](const SpatialHash& self, py::handle keys) { return look_up(self, keys).found; },
          py::arg("keys"), "A bool mask of the keys present.")
      .def(
          "erase",
          [](SpatialHash& self, py::handle keys_obj) {
            const std::vector<glm::uvec3> keys = keys_from(keys_obj);
            py::gil_scoped_release release;
            return self.erase(keys);
          },
          py::arg("keys"), "Erases keys; returns how many were present.")
      .def("__len__", &SpatialHash::size)
      .def_property_readonly("load", &SpatialHash::load)
      .def_property_readonly("memory_bytes", &SpatialHash::memory_bytes)
      .def_property_readonly("table_extent",
                             [](const SpatialHash& self) {
                               return py::make_tuple(self.table_extent().x, self.table_extent().y);
                             })
      .def(
          "stats",
          [](const SpatialHash& self) {
            const spatial::SpatialHashStats s = self.stats();
            return py::dict("slots"_a = s.slots, "keys"_a = s.keys, "tombstones"_a = s.tombstones, "load"_a = s.load,
                            "max_age"_a = s.max_age, "mean_age"_a = s.mean_age,
                            "ages"_a = owned_array(std::vector<std::uint64_t>(s.ages)),
                            "quotient_bits"_a = s.quotient_bits, "memory_bytes"_a = s.memory_bytes,
                            "bytes_per_key"_a = s.bytes_per_key);
          },
          "The table's statistics (habuffer hash stats).")
      .def(
          "table",
          [](py::object self_obj) {
            const SpatialHash& self = self_obj.cast<const SpatialHash&>();
            return readonly_view(self.table().data(), self.table_extent().y, self.table_extent().x, self_obj);
          },
          "The slots as a read-only (Hy, Hx) uint64 view of the table's storage (no copy); a rehash replaces the "
          "storage, so take a new view after inserting.")
      .def(
          "max_age",
          [](py::object self_obj) {
            const SpatialHash& self = self_obj.cast<const SpatialHash&>();
            const std::span<const std::uint32_t> cells = self.max_age();
            return readonly_view(cells.data(), 1, static_cast<py::ssize_t>(cells.size()), self_obj);
          },
          "The max-age cells as a read-only (1, cells) uint32 view.");
}

}  // namespace habuffer::python
