#include "habuffer/harness/sweep.h"
#include "habuffer/technique_descriptor.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "habuffer/age_experiment.h"
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/probe_simulator.h"

namespace habuffer::harness {
namespace {

bool sized_by_load(Technique t) { return descriptor(t).capacity != CapacityKind::None; }

// "ha, lists, ...": the techniques a load sizes, for messages.
std::string sized_techniques() {
  std::string s;
  for (const TechniqueDescriptor* d : technique_registry())
    if (sized_by_load(d->technique)) s += (s.empty() ? "" : ", ") + std::string(d->name);
  return s;
}

// The settings of one run: the technique sized for `load` of `fragments`.
RenderSettings run_settings(const SweepSettings& s, Extent screen, std::uint64_t fragments, double load,
                            std::uint32_t repeat) {
  RenderSettings r;
  r.path = s.path;
  r.threads = s.threads;
  r.insert_order = s.insert_order;
  r.frames = 2;  // a warm-up frame on the same buffers, then the timed one (steady state)
  r.config.screen = screen;
  r.offsets.generator = s.offsets;
  r.offsets.seed = s.seed + repeat;
  r.count_slot_writes = s.path == RenderPath::Gl;  // slot_writes_per_fragment, a column of the GL sweep
  TechniqueSpec t = s.technique;
  t.load.reset();
  t.layers.reset();
  if (uses_layers(t.technique))
    t.layers = static_cast<std::uint32_t>(
        std::max<std::uint64_t>(1, capacity_for_load(fragments, load * static_cast<double>(screen.area()))));
  else
    t.load = load;
  t.apply(r, fragments);
  return r;
}

// Slots probed per insert call by SPEC 3's coherent Robin Hood insertion of
// the same fragments into the same table with the same offsets (the stats
// library's instrumented model builds the very table of the HA-buffer).
double simulated_probes(const ExactCapture& c, const RenderSettings& r) {
  SimulatorConfig sc;
  sc.screen = r.config.screen;
  sc.table = r.config.table_or_screen();
  sc.age_bits = r.config.age_bits;
  sc.block = r.config.block;
  sc.seed = r.offsets.seed;
  sc.offsets = r.offsets.generator;
  sc.iter_limit = r.config.iter_limit;
  ProbeSimulator sim(sc);
  sim.insert(c.stream);
  const SimulatorTotals t = sim.totals();
  return t.counters.fragments ? static_cast<double>(t.probes) / static_cast<double>(t.counters.fragments) : 0.0;
}

struct LoadRuns {
  std::vector<double> mfrag_per_s, gather_ms, mean_age;
  std::vector<double> sort_ms, sorted_ms, sorted_mfrag_per_s;  // the cost to sorted lists (gather + sort pass)
  std::vector<std::uint64_t> histogram;
  std::vector<std::uint32_t> max_age;
  Counters counters;  // summed over the runs
  std::uint64_t slot_writes = 0, memory_bytes = 0, capacity = 0;
  double measured_load = 0.0;
  Extent table;
  double probes = -1.0;
  InsertOrder insert_order = InsertOrder::Arrival;
};

void add_histogram(std::vector<std::uint64_t>& into, const std::vector<std::uint64_t>& h) {
  if (into.size() < h.size()) into.resize(h.size(), 0);
  for (std::size_t i = 0; i < h.size(); ++i) into[i] += h[i];
}

ResultRow make_row(const SweepSettings& s, double load, const LoadRuns& r) {
  ResultRow row;
  row.set("load", load).set("measured_load", r.measured_load).set("technique", s.technique.label())
      .set("insert_order", to_string(r.insert_order))
      .set("repeats", s.repeats).set("capacity", r.capacity);
  if (r.table.area() != 0) row.set("table", r.table.str());
  const Spread m = spread_of(r.mfrag_per_s), g = spread_of(r.gather_ms);
  row.set("mfrag_per_s", m.median).set("mfrag_per_s_min", m.min).set("mfrag_per_s_max", m.max)
      .set("gather_ms", g.median).set("gather_ms_min", g.min).set("gather_ms_max", g.max);
  const Spread sorted = spread_of(r.sorted_mfrag_per_s);
  row.set("sort_ms", spread_of(r.sort_ms).median).set("sorted_ms", spread_of(r.sorted_ms).median)
      .set("sorted_mfrag_per_s", sorted.median).set("sorted_mfrag_per_s_min", sorted.min)
      .set("sorted_mfrag_per_s_max", sorted.max);
  const double calls = static_cast<double>(r.counters.fragments);
  if (s.path == RenderPath::Gl && calls > 0) row.set("slot_writes_per_fragment", static_cast<double>(r.slot_writes) / calls);
  if (r.probes >= 0.0) row.set("probes_per_fragment", r.probes);
  if (!r.histogram.empty()) {
    row.set("mean_age", histogram_mean(r.histogram))
        .set("mean_age_ci95", mean_ci95(r.mean_age))
        .set("p99_age", histogram_quantile(r.histogram, 0.99))
        .set("max_age", *std::max_element(r.max_age.begin(), r.max_age.end()))
        .set("age_histogram", r.histogram);
  }
  set_counters(row, r.counters);
  row.set("memory_bytes", r.memory_bytes);
  return row;
}

}  // namespace

std::vector<std::uint64_t> age_histogram(const FragmentBuffer& buffer) {
  std::vector<std::uint64_t> h;
  std::vector<ListEntry> list;
  for (std::uint32_t y = 0; y < buffer.screen().y; ++y)
    for (std::uint32_t x = 0; x < buffer.screen().x; ++x) {
      buffer.list(x, y, list);
      for (const ListEntry& e : list) {
        if (h.size() <= e.age) h.resize(e.age + 1, 0);
        ++h[e.age];
      }
    }
  return h;
}

double histogram_mean(const std::vector<std::uint64_t>& h) {
  double sum = 0.0, n = 0.0;
  for (std::size_t a = 0; a < h.size(); ++a) {
    sum += static_cast<double>(a) * static_cast<double>(h[a]);
    n += static_cast<double>(h[a]);
  }
  return n > 0 ? sum / n : 0.0;
}

std::uint32_t histogram_quantile(const std::vector<std::uint64_t>& h, double q) {
  std::uint64_t total = 0;
  for (const std::uint64_t c : h) total += c;
  const double want = q * static_cast<double>(total);
  std::uint64_t seen = 0;
  for (std::size_t a = 0; a < h.size(); ++a) {
    seen += h[a];
    if (static_cast<double>(seen) >= want && h[a] > 0) return static_cast<std::uint32_t>(a);
  }
  return h.empty() ? 0 : static_cast<std::uint32_t>(h.size() - 1);
}

void validate_sweep(const SweepSettings& s) {
  if (!sized_by_load(s.technique.technique))
    throw std::invalid_argument("technique " + to_string(s.technique.technique) + " has no size to sweep (" +
                                sized_techniques() + " have)");
  if (s.loads.empty()) throw std::invalid_argument("--loads is empty");
  check_runs_on_path(s.path, s.technique.technique);
  // The sweep sizes the technique itself; a size in the word would be
  // overridden yet kept in the rows' label.
  if (s.technique.load || s.technique.layers)
    throw std::invalid_argument("--technique " + s.technique.label() + ": sweep sets the " +
                                (s.technique.load ? "load" : "layers (k)") + " from --loads; drop it from the word");
  for (std::size_t i = 0; i < s.loads.size(); ++i) {
    if (!(s.loads[i] > 0.0 && s.loads[i] <= 1.0))
      throw std::invalid_argument("--loads: " + std::to_string(s.loads[i]) + " is not in (0, 1]");
    if (i > 0 && !(s.loads[i] > s.loads[i - 1]))
      throw std::invalid_argument("--loads must increase: " + std::to_string(s.loads[i]) + " follows " +
                                  std::to_string(s.loads[i - 1]));
  }
  if (s.repeats == 0) throw std::invalid_argument("--repeats must be at least 1");
}

ResultTable run_sweep(const Workload& workload, const SweepSettings& s) {
  validate_sweep(s);
  const ExactCapture capture = workload.capture();
  if (capture.fragments == 0)
    throw std::invalid_argument("scene '" + workload.label() + "' puts no transparent fragment on the screen at " +
                                workload.size().str() + " (out of view, fully opaque or degenerate): nothing to sweep");
  for (const double load : s.loads) (void)run_settings(s, workload.size(), capture.fragments, load, 0);  // throws early
  std::vector<LoadRuns> runs(s.loads.size());
  const std::uint64_t total = std::uint64_t{s.repeats} * s.loads.size();
  std::uint64_t done = 0;
  ResultTable table;
  for (std::uint32_t rep = 0; rep < s.repeats; ++rep)
    for (std::size_t i = 0; i < s.loads.size(); ++i) {
      const RenderSettings rs = run_settings(s, workload.size(), capture.fragments, s.loads[i], rep);
      const RenderResult r = workload.render(rs);
      const FrameStats& f = r.frames.back();
      LoadRuns& l = runs[i];
      l.gather_ms.push_back(f.gather_ms);
      l.mfrag_per_s.push_back(f.gather_ms > 0 ? static_cast<double>(f.counters.fragments) / (f.gather_ms * 1e3) : 0.0);
      const double to_sorted = f.gather_ms + f.sort_ms;
      l.sort_ms.push_back(f.sort_ms);
      l.sorted_ms.push_back(to_sorted);
      l.sorted_mfrag_per_s.push_back(to_sorted > 0 ? static_cast<double>(f.counters.fragments) / (to_sorted * 1e3) : 0.0);
      l.counters += f.counters;
      l.slot_writes += f.slot_writes.value_or(0);
      l.memory_bytes = r.memory_bytes;
      l.capacity = f.capacity;
      l.table = f.table;
      l.measured_load = f.load_factor;
      l.insert_order = f.insert_order;
      table.provenance.renderer = r.device;
      if (uses_table(rs.technique) && r.buffer) {
        const std::vector<std::uint64_t> h = age_histogram(*r.buffer);
        add_histogram(l.histogram, h);
        l.mean_age.push_back(histogram_mean(h));
        l.max_age.push_back(f.max_age);
        if (rep == 0) l.probes = simulated_probes(capture, rs);
      }
      if (s.on_progress) s.on_progress(++done, total);
    }
  table.title = "sweep";
  table.notes["workload"] = workload.label() + " at " + workload.size().str();
  table.notes["fragments"] = std::to_string(capture.fragments);  // one run's
  table.notes["repeats"] = "runs per load: the counter columns and age_histogram sum them (see counters)";
  table.notes["counters"] =
      "fragments, stored, failures, every counter column and age_histogram are sums over the row's repeats runs "
      "(one run's: divide by repeats; the note fragments is one run's); rates and ages (mfrag_per_s, "
      "slot_writes_per_fragment, mean_age, p99_age, max_age) are per run or over the runs' records";
  table.notes["mfrag_per_s"] =
      "fragments reaching insertion / gather time, median over repeats (min, max beside): the gather only, which "
      "leaves out a separate sort pass (sort_ms); compare techniques by sorted_mfrag_per_s";
  table.notes["sorted_mfrag_per_s"] =
      "fragments reaching insertion / sorted_ms, the cost to sorted lists: gather_ms + sort_ms, where sort_ms is the "
      "lists' and arrays' sort pass on the GPU path and 0 where the gather leaves the lists sorted (the HA-buffer, "
      "sorted-lists, the k-buffer, and every CPU container, whose gather sorts); median over repeats (min, max beside)";
  table.notes["probes_per_fragment"] =
      "slots probed per insert call by the instrumented model of SPEC 3 (stats library) on the same fragments, "
      "table and offsets as repetition 0, in arrival order (the process the statistics describe), whatever "
      "insert_order the timed gather used";
  table.notes["gather_ms"] = "the second frame of the view, on the buffers the first made (steady state)";
  table.notes["mean_age_ci95"] = "half-width of the 95% Student-t interval of the repetitions' mean ages";
  for (std::size_t i = 0; i < s.loads.size(); ++i) table.rows.push_back(make_row(s, s.loads[i], runs[i]));
  return table;
}

}  // namespace habuffer::harness
