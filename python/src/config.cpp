#include "config.h"

#include <pybind11/stl.h>

#include <cmath>
#include <sstream>

#include "arrays.h"
#include "bindings.h"
#include "habuffer/interchange.h"
#include "habuffer/offset_sequence.h"
#include "habuffer/printable.h"
#include "habuffer/technique_descriptor.h"
#include "habuffer/technique_options.h"

namespace habuffer::python {

std::string python_name(std::string_view flag) {
  std::string s(flag);
  for (char& c : s)
    if (c == '-') c = '_';
  return s;
}

namespace {

const TechniqueOption* option_named(const std::string& name) {
  for (const TechniqueOption& o : technique_options())
    if (!o.flag.empty() && python_name(o.flag) == name) return &o;
  return nullptr;
}

// The option's value as the command line would write it, for the table's parser.
std::string option_text(const TechniqueOption& o, py::handle v) {
  const std::string name = python_name(o.flag);
  switch (o.kind) {
    case OptionKind::Switch:
      if (!py::isinstance<py::bool_>(v)) throw py::type_error(name + ": expected True or False");
      return v.cast<bool>() ? "on" : "off";
    case OptionKind::Threshold:
      if (v.is_none()) return "off";
      [[fallthrough]];
    case OptionKind::Load:
      // numpy's scalars too; a bool is no number here (True would read as 1.0)
      if (py::isinstance<py::bool_>(v) || !PyNumber_Check(v.ptr()) || PyComplex_Check(v.ptr()))
        throw py::type_error(name + ": expected a number, got " + py::repr(v).cast<std::string>());
      return py::repr(py::float_(py::reinterpret_borrow<py::object>(v))).cast<std::string>();
    case OptionKind::Interval: {
      std::vector<double> pair;
      try {
        pair = v.cast<std::vector<double>>();
      } catch (const py::cast_error&) {
        throw py::type_error(name + ": expected (near, far), got " + py::repr(v).cast<std::string>());
      }
      if (pair.size() != 2) throw py::value_error(name + ": expected (near, far)");
      std::ostringstream s;
      s.precision(9);
      s << pair[0] << ',' << pair[1];
      return s.str();
    }
    case OptionKind::CountOrAuto:
      if (py::isinstance<py::str>(v)) return v.cast<std::string>();
      [[fallthrough]];
    case OptionKind::Count:
      // Python's and numpy's integers (operator.index), not bools
      if (py::isinstance<py::bool_>(v) || !PyIndex_Check(v.ptr()))
        throw py::type_error(name + ": expected an integer, got " + py::repr(v).cast<std::string>());
      return py::str(py::reinterpret_steal<py::object>(PyNumber_Index(v.ptr()))).cast<std::string>();
  }
  return {};
}

Layout layout_arg(py::handle v) {
  const std::string s = py::str(v).cast<std::string>();
  if (s == "64" || s == "L64") return Layout::L64;
  if (s == "32" || s == "L32") return Layout::L32;
  throw py::value_error("layout: expected 64 or 32, got " + py::repr(v).cast<std::string>());
}

void apply_options(TechniqueConfig& c, const TechniqueDescriptor& d, const py::kwargs& options) {
  std::vector<const TechniqueOption*> given;
  for (const auto& [key, value] : options) {
    const std::string name = key.cast<std::string>();
    const TechniqueOption* o = option_named(name);
    if (!o) throw py::type_error("unknown option '" + name + "'");
    // Age bits and samples fix the record of every technique (TechniqueConfig::validate
    // refuses samples above 1 where no lists are stored); the rest only where the descriptor takes them.
    if (o->flag != "age-bits" && o->flag != "samples" && !d.takes(o->flag))
      throw py::value_error("option " + name + " does not apply to technique " + std::string(d.name) + " (it applies to " +
                            techniques_taking(o->flag) + ")");
    const std::string text = option_text(*o, value);
    try {
      set_option(*o, c, text);
    } catch (const std::invalid_argument& e) {
      throw py::value_error("option " + name + ": " + e.what());
    }
    given.push_back(o);
  }
  for (const TechniqueOption* o : given) {
    if (o->needs.empty()) continue;
    const TechniqueOption* needed = find_option_flag(o->needs);
    if (needed && option_on(*o, c) && !option_on(*needed, c))  // as the CLI: an option left off needs nothing
      throw py::value_error("option " + python_name(o->flag) + " " + std::string(o->without_needed));
  }
}

}  // namespace

TechniqueConfig technique_config_from(const ConfigArgs& a, const py::kwargs& options) {
  const std::optional<Technique> t = parse_technique(a.technique);
  if (!t) {
    std::string names;
    for (const Technique k : all_techniques()) names += (names.empty() ? "" : ", ") + to_string(k);
    throw py::value_error("technique: unknown '" + a.technique + "' (one of " + names + ")");
  }
  const TechniqueDescriptor& d = descriptor(*t);
  TechniqueConfig c;
  c.technique = *t;
  c.buffer.screen = extent_arg(a.screen, "screen");
  if (!a.table.is_none()) {
    if (!d.takes("table"))
      throw py::value_error("table applies to " + techniques_taking("table") + ", not to " + std::string(d.name));
    c.buffer.table = extent_arg(a.table, "table");
  }
  c.buffer.layout = layout_arg(a.layout);
  apply_options(c, d, options);
  try {
    // A pool of 0 is the automatic pool, which build() sizes from the stream
    // (build_technique); the rest of the configuration is checked as given.
    TechniqueConfig checked = c;
    if (uses_pool(c.technique) && checked.pool_capacity == 0) checked.pool_capacity = 1;
    checked.validate();
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  return c;
}

spatial::Domain domain_arg(py::handle obj) {
  std::vector<std::int64_t> d;
  try {
    d = obj.cast<std::vector<std::int64_t>>();
  } catch (const py::cast_error&) {
    throw py::type_error("domain: expected (X, Y) or (X, Y, Z) integers, got " + py::repr(obj).cast<std::string>());
  }
  if (d.size() != 2 && d.size() != 3) throw py::value_error("domain: expected (X, Y) or (X, Y, Z)");
  for (const std::int64_t side : d)
    if (side < 1 || side > UINT32_MAX)
      throw py::value_error("domain: sides must be in [1, 2^32 - 1], got " + py::repr(obj).cast<std::string>());
  return spatial::Domain{static_cast<std::uint32_t>(d[0]), static_cast<std::uint32_t>(d[1]),
                         d.size() == 3 ? static_cast<std::uint32_t>(d[2]) : 1u};
}

RenderPath path_arg(const std::string& p) {
  if (p == "gl") return RenderPath::Gl;
  if (p == "cpu") return RenderPath::Cpu;
#ifdef HABUFFER_WITH_VK
  if (p == "vk") return RenderPath::Vk;
  throw py::value_error("path: '" + p + "' is not gl, cpu or vk");
#else
  throw py::value_error("path: '" + p + "' is not gl or cpu (this habuffer has no Vulkan path)");
#endif
}

OffsetGenerator offsets_arg(const std::string& name) {
  const std::optional<OffsetGenerator> g = parse_offset_generator(name);
  if (!g) throw py::value_error("offsets: expected 'random' or 'farthest', got '" + name + "'");
  return *g;
}

OffsetSource offset_source_from(const ConfigArgs& a) {
  OffsetSource s;
  s.seed = a.seed;
  if (!a.offset_list.is_none()) {
    const auto rows = checked_array<std::uint32_t>(a.offset_list, "offset_list", 2, 2);
    const auto r = rows.unchecked<2>();
    for (py::ssize_t i = 0; i < rows.shape(0); ++i) s.list.emplace_back(r(i, 0), r(i, 1));
    s.generator = OffsetGenerator::List;
  } else {
    s.generator = offsets_arg(a.offsets);
  }
  return s;
}

py::dict config_dict(const TechniqueConfig& c) {
  const TechniqueDescriptor& d = descriptor(c.technique);
  py::dict out;
  out["technique"] = std::string(d.name);
  out["screen"] = py::make_tuple(c.buffer.screen.x, c.buffer.screen.y);
  if (d.takes("table")) out["table"] = py::make_tuple(c.buffer.table_or_screen().x, c.buffer.table_or_screen().y);
  out["layout"] = static_cast<int>(c.buffer.layout);
  for (const TechniqueOption& o : technique_options()) {
    if (o.flag.empty() || !o.get || (o.flag != "age-bits" && !d.takes(o.flag))) continue;
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, DepthRange>)
            out[python_name(o.flag).c_str()] = py::make_tuple(v.near_t, v.far_t);
          else
            out[python_name(o.flag).c_str()] = v;
        },
        o.get(c));
  }
  return out;
}

void bind_config(py::module_& m) {
  m.def(
      "techniques",
      [] {
        py::list out;
        for (const Technique t : all_techniques()) {
          const TechniqueDescriptor& d = descriptor(t);
          py::dict row;
          row["name"] = std::string(d.name);
          row["summary"] = std::string(d.summary);
          row["stores_lists"] = d.stores_lists;
          row["exact"] = d.exact;
          row["early_cull"] = d.early_cull;
          row["sorted_on_insert"] = d.sorted_on_insert;
          py::list opts;
          for (const TechniqueOption& o : technique_options())
            if (!o.flag.empty() && (o.flag == "age-bits" || d.takes(o.flag))) opts.append(python_name(o.flag));
          row["options"] = opts;
          const TechniqueProperties& p = d.properties;
          row["source"] = std::string(p.source);
          row["storage"] = std::string(p.storage);
          row["bytes_per_fragment"] = std::string(p.bytes_per_fragment);
          row["passes"] = std::string(p.passes);
          row["atomics_per_fragment"] = std::string(p.atomics_per_fragment);
          row["sorted"] = std::string(p.sorted);
          row["exact_when"] = std::string(p.exact_when);
          row["overflow"] = std::string(p.overflow);
          out.append(row);
        }
        return out;
      },
      "Every registered technique with its properties (the README's table, as data) and the options it takes.");
  m.def(
      "offsets",
      [](py::handle table, const IntArg& count, const std::string& generator, const IntArg& seed) {
        ConfigArgs a;
        a.offsets = generator;
        a.seed = seed_arg(seed);
        const std::uint32_t n = u32_arg(count, "count", 1, 1u << 20);  // as habuffer offsets --count
        const OffsetSource source = offset_source_from(a);
        const OffsetSequence o = source.make(extent_arg(table, "table"), n);
        std::vector<std::uint32_t> flat;
        for (const glm::uvec2 v : o.values()) flat.insert(flat.end(), {v.x, v.y});
        return owned_array(std::move(flat)).reshape({static_cast<py::ssize_t>(o.size()), py::ssize_t{2}});
      },
      py::arg("table"), py::arg("count"), py::arg("generator") = "random", py::arg("seed") = 1,
      "The first `count` offsets (SPEC 3) for a table of (W, H): a (count, 2) uint32 array.");
  m.def(
      "read_fragments",
      [](const std::string& path, py::handle screen, bool with_coverage) {
        const std::vector<Fragment> f = read_fragments(path, extent_arg(screen, "screen"));
        std::vector<std::uint32_t> xy, rgba, coverage;
        std::vector<float> depth;
        xy.reserve(2 * f.size());
        for (std::size_t i = 0; i < f.size(); ++i) {
          const Fragment& g = f[i];
          // A mask never dropped silently: a stream that carries them is read with them.
          if (g.coverage != 0 && !with_coverage)
            throw py::value_error(printable(path) + ": fragment " + std::to_string(i + 1) +
                                  " carries a coverage mask (" + std::to_string(g.coverage) +
                                  "): read it with coverage=True and pass coverage= to build or insert");
          xy.insert(xy.end(), {g.x, g.y});
          depth.push_back(g.depth);
          rgba.push_back(g.rgba);
          coverage.push_back(g.coverage);
        }
        py::array xy_array = owned_array(std::move(xy)).reshape({static_cast<py::ssize_t>(f.size()), py::ssize_t{2}});
        if (with_coverage)
          return py::make_tuple(xy_array, owned_array(std::move(depth)), owned_array(std::move(rgba)),
                                owned_array(std::move(coverage)));
        return py::make_tuple(xy_array, owned_array(std::move(depth)), owned_array(std::move(rgba)));
      },
      py::arg("path"), py::arg("screen"), py::kw_only(), py::arg("coverage") = false,
      "A fragment CSV (x,y,depth,rgba[,coverage]) as (xy, depth, rgba) arrays, parsed as habuffer build-lists "
      "parses it; with coverage=True (xy, depth, rgba, coverage), the sample masks for build or insert's "
      "coverage= (a stream holding masks read without it raises ValueError: nothing is dropped silently).");
  m.attr("FRAGMENT_DTYPE") = fragment_dtype();
}

}  // namespace habuffer::python
