// The statistics experiments and the harness from Python: each returns its
// result table as a habuffer.Table (a dict of numpy arrays, one per column,
// with the table's title, notes and provenance as attributes), ready for
// pandas.DataFrame(table). Settings default to the library's own (the C++
// settings structs' initializers); words (scenes, technique words) are read
// by the harness' parsers, so they take what the CLI takes.
#include <pybind11/stl.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#include "arrays.h"
#include "bindings.h"
#include "config.h"
#include "gl_context.h"
#include "habuffer/age_experiment.h"
#include "habuffer/experiment_columns.h"
#include "habuffer/harness/bench.h"
#include "habuffer/harness/figures.h"
#include "habuffer/harness/frontier.h"
#include "habuffer/harness/plan.h"
#include "habuffer/harness/sweep.h"
#include "habuffer/key_experiment.h"
#include "habuffer/option_rules.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::python {
namespace {

using namespace pybind11::literals;
using harness::Cell;
using harness::ResultTable;

// One column of cells as the narrowest numpy array that holds them: int64
// (no gaps), float64 (NaN for gaps), bool, or objects (text, histograms,
// gaps among them as None).
py::object column_array(const std::vector<const Cell*>& cells) {
  bool ints = true, reals = true, bools = true;
  std::size_t gap_count = 0;
  for (const Cell* c : cells) {
    if (!c || std::holds_alternative<std::monostate>(*c)) {
      ++gap_count;
      continue;
    }
    const bool is_int = std::holds_alternative<std::int64_t>(*c), is_real = std::holds_alternative<double>(*c);
    ints &= is_int;
    reals &= is_int || is_real;
    bools &= std::holds_alternative<bool>(*c);
  }
  const std::size_t n = cells.size();
  const bool gaps = gap_count > 0, all_gaps = gap_count == n;
  if (ints && !gaps && !all_gaps) {
    std::vector<std::int64_t> v(n);
    for (std::size_t i = 0; i < n; ++i) v[i] = std::get<std::int64_t>(*cells[i]);
    return owned_array(std::move(v));
  }
  if (reals || all_gaps) {
    std::vector<double> v(n, std::numeric_limits<double>::quiet_NaN());
    for (std::size_t i = 0; i < n; ++i)
      if (cells[i]) {
        if (const auto* d = std::get_if<double>(cells[i])) v[i] = *d;
        if (const auto* k = std::get_if<std::int64_t>(cells[i])) v[i] = static_cast<double>(*k);
      }
    return owned_array(std::move(v));
  }
  if (bools && !gaps) {
    py::array_t<bool> v(static_cast<py::ssize_t>(n));
    for (std::size_t i = 0; i < n; ++i) v.mutable_at(static_cast<py::ssize_t>(i)) = std::get<bool>(*cells[i]);
    return v;
  }
  py::list items;
  for (const Cell* c : cells) {
    if (!c) {
      items.append(py::none());
      continue;
    }
    std::visit(
        [&](const auto& v) {
          using V = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<V, std::monostate>)
            items.append(py::none());
          else if constexpr (std::is_same_v<V, std::vector<std::uint64_t>>)
            items.append(owned_array(std::vector<std::uint64_t>(v)));
          else
            items.append(py::cast(v));
        },
        *c);
  }
  return py::module_::import("numpy").attr("array")(items, "dtype"_a = "object");
}

py::object table_object(const ResultTable& t) {
  py::object table = py::module_::import("habuffer").attr("Table")();
  for (const std::string& name : t.columns()) {
    std::vector<const Cell*> cells;
    cells.reserve(t.rows.size());
    for (const harness::ResultRow& r : t.rows) cells.push_back(r.find(name));
    table[py::str(name)] = column_array(cells);
  }
  table.attr("title") = t.title;
  table.attr("notes") = py::cast(t.notes);
  py::dict prov;
  prov["command"] = t.provenance.command;
  prov["machine"] = t.provenance.machine;
  prov["renderer"] = t.provenance.renderer;
  table.attr("provenance") = prov;
  return table;
}

// Rows of a statistics experiment as a Table, by the rows' column list.
template <class Row>
py::object rows_table(const std::vector<Row>& rows, std::span<const RowColumn<Row>> columns, const char* title) {
  py::object table = py::module_::import("habuffer").attr("Table")();
  for (const RowColumn<Row>& col : columns) {
    py::list values;
    for (const Row& r : rows) std::visit([&](const auto& v) { values.append(py::cast(v)); }, col.get(r));
    const char* dtype = "float64";  // (an empty table's columns too)
    if (!rows.empty()) {
      const ColumnValue first = col.get(rows.front());
      dtype = std::holds_alternative<std::string>(first) ? "object"
              : std::holds_alternative<double>(first)    ? "float64"
                                                         : "uint64";
    }
    table[py::str(std::string(col.name))] = py::module_::import("numpy").attr("array")(values, "dtype"_a = dtype);
  }
  table.attr("title") = title;
  return table;
}

InsertOrder order_arg(const std::string& o) {
  const std::optional<InsertOrder> parsed = parse_insert_order(o);
  if (!parsed) throw py::value_error("order: '" + o + "' is not auto, arrival or pixel");
  return *parsed;
}

std::vector<harness::WorkloadSpec> workloads(const std::vector<std::string>& words) {
  std::vector<harness::WorkloadSpec> out;
  for (const std::string& w : words) out.push_back(harness::parse_workload_spec(w));
  return out;
}

bool needs_context(const std::vector<harness::WorkloadSpec>& w) {
  return std::any_of(w.begin(), w.end(), [](const harness::WorkloadSpec& s) { return s.fragments.empty(); });
}

// Runs `run` with the module's GL context current when a scene needs it, the GIL released.
template <class Run>
ResultTable with_context(bool needed, Run run) {
  // The GIL first, then the context's lock (and the lock released before the
  // GIL is taken back): a thread never waits for one holding the other.
  py::gil_scoped_release release;
  std::optional<GlContextUse> use;
  if (needed) use.emplace();
  return run();
}

// repeats in 1..1000, as every --repeats.
std::uint32_t repeats_arg(const IntArg& repeats) { return u32_arg(repeats, "repeats", 1, 1000); }

// The harness calls' shared rules, as the CLI's: repeats in 1..1000, threads on the CPU path only.
void check_runs(std::uint32_t repeats, RenderPath path, std::uint32_t threads) {
  if (repeats < 1 || repeats > 1000) throw py::value_error("repeats: " + std::to_string(repeats) + " outside 1..1000");
  if (path != RenderPath::Cpu && threads != 0)
    throw py::value_error("threads: the CPU path's (path='cpu'); with path='" + std::string(to_string(path)) +
                          "' the GPU inserts");
}

harness::FigureSettings figure_settings(const std::string& path, py::handle size, const IntArg& repeats,
                                        const IntArg& threads, float tau) {
  harness::FigureSettings f;
  f.path = path_arg(path);
  if (f.path == RenderPath::Vk)  // as habuffer figure: vk renders frontier
    throw py::value_error("path: 'vk' runs bench, sweep and frontier; this figure runs on gl or cpu");
  f.repeats = repeats_arg(repeats);
  f.threads = threads_arg(threads);
  check_runs(f.repeats, f.path, f.threads);
  f.tau = parse_cull_threshold(py::repr(py::float_(tau)).cast<std::string>());  // in (0, 1], as --tau
  f.size = extent_arg(size, "size");
  return f;
}

harness::Provenance provenance(const std::string& call) {
  return {"python: habuffer." + call, harness::machine_description(), ""};
}

// `run` on the workload of `word` at `size` (the module's context current
// for a scene), its table with the call's provenance.
template <class Run>
py::object on_workload(const std::string& word, py::handle size, const char* call, Run run) {
  const harness::WorkloadSpec spec = harness::parse_workload_spec(word);
  const Extent e = extent_arg(size, "size");
  ResultTable t = with_context(spec.fragments.empty(), [&] {
    const harness::Workload workload(spec, e);
    return run(workload);
  });
  t.provenance = provenance(call);
  return table_object(t);
}

py::object age_experiment(py::handle screen, py::handle table, const std::vector<double>& loads, const IntArg& trials,
                          const IntArg& seed, const std::string& stream, double spread,
                          const std::vector<std::string>& probing, const std::vector<std::string>& policy,
                          const std::vector<std::string>& offsets, const IntArg& age_bits, const IntArg& block) {
  ExperimentConfig c;
  c.screen = extent_arg(screen, "screen");
  c.table = table.is_none() ? c.screen : extent_arg(table, "table");
  c.loads = loads;
  c.trials = u32_arg(trials, "trials", 1, 100000);  // habuffer stats' ranges
  c.seed = seed_arg(seed);
  c.age_bits = u32_arg(age_bits, "age_bits", HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  c.block = u32_arg(block, "block", 1, 1u << 16);
  c.stream = experiment_stream(parse_stream_kind(stream), spread, c.age_bits);
  c.variants = variant_grid(parse_probings(probing), parse_policies(policy), parse_offset_generators(offsets));
  validate_experiment(c);  // the CLI's rules (ValueError naming the field)
  std::vector<ExperimentRow> rows;
  {
    py::gil_scoped_release release;
    rows = run_age_experiment(c);
  }
  return rows_table(rows, experiment_columns(), "stats");
}

py::object key_experiment(const std::string& keys, py::handle domain, double coverage, const IntArg& count,
                          const std::vector<double>& loads, const IntArg& trials, const IntArg& seed_obj,
                          const std::vector<std::string>& probing, const std::vector<std::string>& policy,
                          const IntArg& age_bits, const IntArg& block, const IntArg& misses) {
  const std::uint64_t seed = seed_arg(seed_obj);
  spatial::KeyExperimentConfig c;
  const std::optional<spatial::KeySet> set = spatial::parse_key_set(keys);
  if (!set) throw py::value_error("keys: unknown key set '" + keys + "'");
  c.keys.set = *set;
  c.keys.domain = domain_arg(domain);
  c.keys.coverage = coverage;
  c.keys.count = uint_arg(count, "count", 1, UINT64_MAX);  // habuffer stats --keys' ranges
  c.keys.seed = seed;
  c.loads = loads;
  c.trials = u32_arg(trials, "trials", 1, 1000);
  c.seed = seed;
  c.age_bits = u32_arg(age_bits, "age_bits", HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  c.block = u32_arg(block, "block", 1, 1u << 16);
  c.misses = u32_arg(misses, "misses", 0, 10000000);
  c.probing = spatial::parse_key_probings(probing);
  c.policy = spatial::parse_key_policies(policy);
  std::vector<spatial::KeyExperimentRow> rows;
  {
    py::gil_scoped_release release;
    rows = spatial::run_key_experiment(c);
  }
  return rows_table(rows, key_experiment_columns(), "stats --keys");
}

py::object sweep(const std::string& scene, const std::string& technique, const std::vector<double>& loads,
                 py::handle size, const IntArg& repeats, const std::string& path, const IntArg& seed,
                 const std::string& offsets, const IntArg& threads, const std::string& order) {
  harness::SweepSettings s;
  s.technique = harness::parse_technique_spec(technique);
  s.loads = loads;
  s.repeats = repeats_arg(repeats);
  s.path = path_arg(path);
  s.threads = threads_arg(threads);
  check_runs(s.repeats, s.path, s.threads);
  s.seed = seed_arg(seed);
  s.offsets = offsets_arg(offsets);
  s.insert_order = order_arg(order);
  harness::validate_sweep(s);
  return on_workload(scene, size, "sweep", [&](const harness::Workload& w) { return harness::run_sweep(w, s); });
}

py::object bench(const std::vector<std::string>& scenes, const std::vector<std::string>& techniques,
                 const std::vector<py::object>& sizes, const IntArg& repeats, const std::string& path,
                 const IntArg& threads, const IntArg& seed, bool floors, const std::string& order) {
  harness::BenchSettings b;
  b.scenes = workloads(scenes);
  for (const std::string& t : techniques) b.techniques.push_back(harness::parse_technique_spec(t));
  for (const py::object& s : sizes) b.sizes.push_back(extent_arg(s, "sizes"));
  b.repeats = repeats_arg(repeats);
  b.path = path_arg(path);
  b.threads = threads_arg(threads);
  check_runs(b.repeats, b.path, b.threads);
  b.seed = seed_arg(seed);
  b.floors = floors;
  b.insert_order = order_arg(order);
  harness::validate_bench(b);
  ResultTable t = with_context(needs_context(b.scenes), [&] { return harness::run_bench(b); });
  t.provenance = provenance("bench");
  return table_object(t);
}

py::object frontier(const std::vector<std::string>& scenes, const std::vector<py::object>& sizes, const IntArg& repeats,
                    const std::string& path, const IntArg& threads, const std::vector<double>& targets) {
  harness::BenchSettings b;
  b.scenes = workloads(scenes);
  for (const py::object& s : sizes) b.sizes.push_back(extent_arg(s, "sizes"));
  b.path = path_arg(path);
  b.repeats = repeats_arg(repeats);
  b.threads = threads_arg(threads);
  check_runs(b.repeats, b.path, b.threads);
  b.techniques = harness::frontier_techniques(b.path);
  harness::validate_bench(b);
  ResultTable t = with_context(true, [&] { return harness::run_bench(b); });
  t.title = "frontier";
  t.provenance = provenance("frontier");
  harness::mark_pareto(t);
  ResultTable picks = harness::frontier_picks(t, targets);
  picks.provenance = t.provenance;
  return py::make_tuple(table_object(t), table_object(picks));
}

py::object plan(const std::string& scene, py::handle size, std::optional<double> target_psnr,
                const std::vector<double>& loads, const IntArg& trials, const IntArg& seed, const IntArg& age_bits) {
  harness::PlanSettings p;
  if (target_psnr && !(std::isfinite(*target_psnr) && *target_psnr > 0.0))
    throw py::value_error("target_psnr: " + py::repr(py::float_(*target_psnr)).cast<std::string>() +
                          " is not a finite PSNR above 0 dB");
  p.target_psnr = target_psnr;
  p.loads = loads;
  p.trials = u32_arg(trials, "trials", 1, 1000);  // habuffer plan's ranges
  p.seed = seed_arg(seed);
  p.age_bits = u32_arg(age_bits, "age_bits", HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  return on_workload(scene, size, "plan", [&](const harness::Workload& w) { return harness::run_plan(w, p); });
}

py::object figure_fig2(const std::string& scene, const std::vector<float>& opacities, py::handle size,
                       const IntArg& repeats, const std::string& path, const IntArg& threads, float tau) {
  const harness::FigureSettings f = figure_settings(path, size, repeats, threads, tau);
  const harness::WorkloadSpec w = harness::parse_workload_spec(scene);
  harness::check_fig2_scene(w);
  std::vector<float> checked;
  SceneOptions probe;  // each opacity by the scene option's rule, as habuffer figure fig2
  for (const float o : opacities) {
    set_scene_option(probe, "opacity", py::repr(py::float_(o)).cast<std::string>());
    checked.push_back(probe.opacity);
  }
  ResultTable t = with_context(true, [&] { return harness::run_fig2(w, checked, f); });
  t.provenance = provenance("figure_fig2");
  return table_object(t);
}

py::object figure_fig8(const std::string& scene, const IntArg& frames_obj, double load, py::handle size,
                       const IntArg& repeats, const std::string& path, const IntArg& threads, float tau) {
  const std::uint32_t frames = u32_arg(frames_obj, "frames", 2, 100000);  // as habuffer figure fig8 --frames
  const harness::FigureSettings f = figure_settings(path, size, repeats, threads, tau);
  const harness::WorkloadSpec w = harness::parse_workload_spec(scene);
  harness::check_fig8_scene(w);
  ResultTable t = with_context(true, [&] { return harness::run_fig8(w, frames, load, f); });
  t.provenance = provenance("figure_fig8");
  return table_object(t);
}

py::object figure_fig10(const IntArg& planes_obj, py::handle size, const IntArg& repeats, const std::string& path,
                        const IntArg& threads) {
  const std::uint32_t planes = u32_arg(planes_obj, "planes", 1, 4096);
  const harness::FigureSettings f = figure_settings(path, size, repeats, threads, harness::FigureSettings{}.tau);
  harness::BenchSettings b = harness::fig10_bench_settings(planes, f);
  harness::validate_bench(b);
  ResultTable t = with_context(true, [&] { return harness::run_bench(b); });
  t.title = "fig10";
  t.provenance = provenance("figure_fig10");
  return table_object(t);
}

py::object memory_table(py::handle screen, const std::vector<IntArg>& fragment_counts,
                        const std::vector<double>& loads, bool allocate) {
  const Extent e = extent_arg(screen, "screen");
  std::vector<std::uint64_t> fragments;
  for (std::size_t i = 0; i < fragment_counts.size(); ++i)
    fragments.push_back(uint_arg(fragment_counts[i], "fragments[" + std::to_string(i) + "]", 0, UINT64_MAX));
  harness::validate_memory_table(e, fragments, loads);
  ResultTable t;
  {
    py::gil_scoped_release release;
    t = harness::run_memory_table(e, fragments, loads, allocate);
  }
  t.provenance = provenance("memory_table");
  return table_object(t);
}

}  // namespace

void bind_results(py::module_& m) {
  m.def("age_experiment", &age_experiment, py::kw_only(), py::arg("screen") = py::make_tuple(128, 128),
        py::arg("table") = py::none(), py::arg("loads") = std::vector<double>{0.5, 0.8, 0.9}, py::arg("trials") = 5,
        py::arg("seed") = 1, py::arg("stream") = "random", py::arg("spread") = 1.0,
        py::arg("probing") = std::vector<std::string>{"coherent", "independent"},
        py::arg("policy") = std::vector<std::string>{"robinhood"},
        py::arg("offsets") = std::vector<std::string>{"random"}, py::arg("age_bits") = 8, py::arg("block") = 8,
        "Age against load (habuffer stats): every variant (probing x policy x offsets) on the same seeded streams; "
        "one row per load and variant with the mean age and its 95% confidence half-width over trials, quantiles, "
        "the rank bound, probes and failures. The same seeds give habuffer stats' numbers.");
  m.def("key_experiment", &key_experiment, py::kw_only(), py::arg("keys") = "sparse-image",
        py::arg("domain") = py::make_tuple(2048, 2048), py::arg("coverage") = 0.25, py::arg("count") = 100000,
        py::arg("loads") = std::vector<double>{0.5, 0.8, 0.9, 0.95, 0.99}, py::arg("trials") = 5, py::arg("seed") = 1,
        py::arg("probing") = std::vector<std::string>{"coherent", "independent"},
        py::arg("policy") = std::vector<std::string>{"robinhood", "fcfs"}, py::arg("age_bits") = 8,
        py::arg("block") = 8, py::arg("misses") = 10000,
        "The spatial hash's key streams (habuffer stats --keys): age, reads per hit and per miss, failures.");

  m.def("sweep", &sweep, py::arg("scene"), py::kw_only(), py::arg("technique") = "ha",
        py::arg("loads") = std::vector<double>{0.5, 0.8, 0.9}, py::arg("size") = py::make_tuple(256, 256),
        py::arg("repeats") = 3, py::arg("path") = "gl", py::arg("seed") = 1, py::arg("offsets") = "random",
        py::arg("threads") = 0, py::arg("order") = "auto",
        "habuffer sweep: one fixed view of `scene` (a scene word such as 'hairball:opacity=0.25', a mesh file, or a "
        "fragment CSV on path='cpu') with the technique sized for each load; one row per load (throughput, probes, "
        "ages, counters, memory).");
  m.def("bench", &bench, py::arg("scenes"), py::kw_only(),
        py::arg("techniques") = std::vector<std::string>{"ha", "lists"},
        py::arg("sizes") = std::vector<py::object>{py::make_tuple(256, 256)}, py::arg("repeats") = 3,
        py::arg("path") = "gl", py::arg("threads") = 0, py::arg("seed") = 1, py::arg("floors") = true,
        py::arg("order") = "auto",
        "habuffer bench: techniques (words such as 'kbuffer:k=8:occ') on scenes and sizes, rounds interleaved; one "
        "row per technique, scene and size (times, memory, counters, PSNR against the exact reference).");
  m.def("frontier", &frontier, py::arg("scenes"), py::kw_only(),
        py::arg("sizes") = std::vector<py::object>{py::make_tuple(256, 256)}, py::arg("repeats") = 3,
        py::arg("path") = "gl", py::arg("threads") = 0, py::arg("targets") = std::vector<double>{30.0, 40.0, 50.0},
        "habuffer figure frontier: every technique and knob of the frontier set, Pareto rows marked; returns (table, "
        "picks), picks being the cheapest row reaching each target PSNR (dB).");
  m.def("plan", &plan, py::arg("scene"), py::kw_only(), py::arg("size") = py::make_tuple(256, 256),
        py::arg("target_psnr") = py::none(), py::arg("loads") = std::vector<double>{0.5, 0.6, 0.7, 0.8, 0.9, 0.95},
        py::arg("trials") = 3, py::arg("seed") = 1, py::arg("age_bits") = HABUFFER_DEFAULT_AGE_BITS,
        "habuffer plan: every technique's predicted memory and accuracy for the scene, the recommendation in "
        "table.notes['recommendation'].");
  m.def("figure_fig2", &figure_fig2, py::arg("scene") = "hairball", py::kw_only(),
        py::arg("opacities") = std::vector<float>{0.125f, 0.25f, 0.5f, 1.0f},
        py::arg("size") = py::make_tuple(256, 256), py::arg("repeats") = 3, py::arg("path") = "gl",
        py::arg("threads") = 0, py::arg("tau") = 0.99f,
        "habuffer figure fig2: frame time and early cull's gain against the scene's opacity.");
  m.def("figure_fig8", &figure_fig8, py::arg("scene") = "quads:count=64", py::kw_only(), py::arg("frames") = 16,
        py::arg("load") = 0.64, py::arg("size") = py::make_tuple(256, 256), py::arg("repeats") = 3,
        py::arg("path") = "gl", py::arg("threads") = 0, py::arg("tau") = 0.99f,
        "habuffer figure fig8 (seed 000 Fig. 8): quads pulled together over `frames` frames into a table fixed at "
        "`load`; time and max age per frame, with and without cull.");
  m.def("figure_fig10", &figure_fig10, py::arg("planes") = 32, py::kw_only(),
        py::arg("size") = py::make_tuple(256, 256), py::arg("repeats") = 3, py::arg("path") = "gl",
        py::arg("threads") = 0,
        "habuffer figure fig10 (seed 001 Fig. 10): N planes front to back and back to front, ha and sorted-lists.");
  m.def("memory_table", &memory_table, py::arg("screen"), py::kw_only(), py::arg("fragments"),
        py::arg("loads") = std::vector<double>{0.5, 0.8}, py::arg("allocate") = false,
        "habuffer figure table1: every technique's memory by its model and by seed 000's Table 1 formula "
        "(allocate=True also builds each container and reports its measured bytes).");
}

}  // namespace habuffer::python
