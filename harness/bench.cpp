#include "habuffer/harness/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "habuffer/harness/floors.h"
#include "habuffer/harness/gpu_model.h"
#include "habuffer/parallel.h"

namespace habuffer::harness {
namespace {

// Untimed frames before the timed one, on the same buffers.
constexpr std::uint32_t kWarmupFrames = 1;

// One workload at one size, made and captured once.
struct Case {
  std::unique_ptr<Workload> workload;
  ExactCapture capture;
  std::unique_ptr<FloorMeter> floors;
  std::vector<double> atomic_ms, blend_ms, exact_ms;
};

struct Cell3 {  // one technique on one case, over the rounds
  std::vector<double> gather_ms, resolve_ms, total_ms, first_frame_ms, clear_ms;
  FrameStats last;
  std::uint64_t memory_bytes = 0, memory_model_bytes = 0;
  ImageDifference error;
  std::string device;
  TechniqueConfig config;  // as the first round ran it (the table resolved): the GPU model's
  OffsetSource offsets;
};

ResultRow make_row(const BenchSettings& s, const TechniqueSpec& t, const Case& c, const Cell3& r,
                   const std::optional<GpuTraffic>& traffic) {
  ResultRow row;
  row.set("technique", t.label()).set("scene", c.workload->label()).set("size", c.workload->size().str())
      .set("path", std::string(to_string(s.path))).set("repeats", s.repeats);
  const Spread g = spread_of(r.gather_ms), v = spread_of(r.resolve_ms), total = spread_of(r.total_ms);
  row.set("gather_ms", g.median).set("gather_ms_min", g.min).set("gather_ms_max", g.max).set("resolve_ms", v.median)
      .set("total_ms", total.median).set("total_ms_min", total.min).set("total_ms_max", total.max)
      .set("first_frame_ms", spread_of(r.first_frame_ms).median).set("clear_ms", spread_of(r.clear_ms).median)
      .set("insert_order", to_string(r.last.insert_order));
  row.set("memory_bytes", r.memory_bytes).set("memory_model_bytes", r.memory_model_bytes);
  const double frags = static_cast<double>(c.capture.fragments);
  row.set("bytes_per_fragment", frags > 0 ? static_cast<double>(r.memory_bytes) / frags : 0.0);
  set_counters(row, r.last.counters);
  if (uses_table(t.technique)) row.set("max_age", r.last.max_age).set("table", r.last.table.str());
  row.set("load_factor", r.last.load_factor);
  row.set("psnr", r.error.psnr).set("rmse", r.error.rmse).set("max_error", r.error.max_error);
  if (!c.atomic_ms.empty()) {
    const double atomic = spread_of(c.atomic_ms).median, blend = spread_of(c.blend_ms).median;
    row.set("atomic_floor_ms", atomic).set("blend_floor_ms", blend);
    row.set("gather_vs_atomic_floor", atomic > 0 ? g.median / atomic : 0.0)
        .set("total_vs_blend_floor", blend > 0 ? total.median / blend : 0.0);
    if (s.path == RenderPath::Cpu) {
      const double exact = spread_of(c.exact_ms).median;
      row.set("exact_floor_ms", exact).set("total_vs_exact_floor", exact > 0 ? total.median / exact : 0.0);
    }
  }
  row.set("device", r.device);
  if (traffic) set_gpu_model_columns(row, *traffic, GpuCostModel::h100());
  return row;
}

}  // namespace

void validate_bench(const BenchSettings& s) {
  if (s.scenes.empty()) throw std::invalid_argument("--scenes is empty");
  if (s.techniques.empty()) throw std::invalid_argument("--techniques is empty");
  if (s.sizes.empty()) throw std::invalid_argument("--size is empty");
  if (s.repeats == 0) throw std::invalid_argument("--repeats must be at least 1");
  for (const TechniqueSpec& t : s.techniques) check_runs_on_path(s.path, t.technique);
  for (const WorkloadSpec& w : s.scenes) {
    if (s.path != RenderPath::Cpu && !w.fragments.empty())
      throw std::invalid_argument("fragment stream '" + w.word + "' renders on the CPU path only (--path cpu)");
    if (w.samples > 1 && std::none_of(s.techniques.begin(), s.techniques.end(),
                                      [&](const TechniqueSpec& t) { return bench_cell_applies(t, w); }))
      throw std::invalid_argument("scene '" + w.word + "' is multisampled: none of the techniques keeps coverage "
                                  "masks (list techniques without early cull only)");
  }
}

bool bench_cell_applies(const TechniqueSpec& t, const WorkloadSpec& w) {
  return w.samples <= 1 || (stores_lists(t.technique) && t.cull <= 0.0f);
}

namespace {

std::vector<Case> make_cases(const BenchSettings& s) {
  std::vector<Case> cases;
  for (const Extent size : s.sizes)
    for (const WorkloadSpec& w : s.scenes) {
      Case c;
      c.workload = std::make_unique<Workload>(w, size);
      c.capture = c.workload->capture();
      cases.push_back(std::move(c));
    }
  // No floors on vk: GL's time GL's rasterizer, the CPU's the CPU; neither is the Vulkan device's.
  if (s.floors && s.path != RenderPath::Vk)
    for (Case& c : cases) c.floors = std::make_unique<FloorMeter>(*c.workload, c.capture, s.path, s.threads);
  return cases;
}

// A scene that puts no transparent fragment on the screen (out of view, fully
// opaque, degenerate) gives rows of 0 fragments timing an empty pass: said
// once per scene, naming it and the sizes, before any work, and kept in the
// table's notes.
void warn_empty_scenes(const BenchSettings& s, const std::vector<Case>& cases, ResultTable& table) {
  std::vector<std::pair<std::string, std::string>> empty;  // the scene's label, its sizes
  for (const Case& c : cases) {
    if (c.capture.fragments != 0) continue;
    const std::string label = c.workload->label(), size = c.workload->size().str();
    const auto it = std::find_if(empty.begin(), empty.end(), [&](const auto& e) { return e.first == label; });
    if (it == empty.end()) empty.emplace_back(label, size);
    else it->second += ", " + size;
  }
  std::string all;
  // The blended baselines store no lists, so a multisampled scene has no row of theirs.
  std::string skipped_techniques, skipped_scenes;
  WorkloadSpec multisampled;
  multisampled.samples = 2;
  for (const TechniqueSpec& t : s.techniques)
    if (!bench_cell_applies(t, multisampled)) skipped_techniques += (skipped_techniques.empty() ? "" : ", ") + t.label();
  for (const WorkloadSpec& w : s.scenes)
    if (w.samples > 1) skipped_scenes += (skipped_scenes.empty() ? "'" : ", '") + w.word + "'";
  if (!skipped_techniques.empty() && !skipped_scenes.empty()) {
    const std::string line = "techniques " + skipped_techniques + " have no rows for the multisampled scenes " +
                             skipped_scenes + " (no lists to keep coverage masks in, or early cull, whose opacity is "
                             "a whole pixel's)";
    if (s.on_warning) s.on_warning(line);
    else std::fprintf(stderr, "habuffer bench: warning: %s\n", line.c_str());
    all += line;
  }
  for (const auto& [scene, sizes] : empty) {
    const std::string line = "scene '" + scene + "' puts no transparent fragment on the screen at " + sizes +
                             " (out of view, fully opaque or degenerate): its rows time an empty pass (0 fragments)";
    if (s.on_warning) s.on_warning(line);
    else std::fprintf(stderr, "habuffer bench: warning: %s\n", line.c_str());
    all += (all.empty() ? "" : "; ") + line;
  }
  if (!all.empty()) table.notes["warnings"] = all;
}

// One round of technique `t` on case `c`, added to `cell`; returns the device.
std::string measure_cell(const BenchSettings& s, const TechniqueSpec& t, const Case& c, bool first_round, Cell3& cell) {
  RenderSettings rs;
  rs.path = s.path;
  rs.threads = s.threads;
  rs.config.screen = c.workload->size();
  rs.config.samples = c.workload->spec().samples;  // Workload::render sets it too; the cell's config records it
  rs.offsets.seed = s.seed;
  rs.background = glm::vec3(1.0f);
  rs.insert_order = s.insert_order;
  // Steady state: frame 0 pays the cold start (fresh buffers, first touch of
  // their pages), frame 1 of the same view on the kept buffers is the one
  // timed; frame 0 is reported beside it.
  rs.frames = kWarmupFrames + 1;
  rs.orbit = false;
  t.apply(rs, c.capture.fragments);
  const RenderResult r = c.workload->render(rs);
  const FrameStats& f = r.frames.back();
  cell.first_frame_ms.push_back(r.frames.front().gather_ms + r.frames.front().resolve_ms);
  cell.clear_ms.push_back(f.clear_ms);
  cell.gather_ms.push_back(f.gather_ms);
  cell.resolve_ms.push_back(f.resolve_ms);
  cell.total_ms.push_back(f.gather_ms + f.resolve_ms);
  cell.last = f;
  cell.memory_bytes = r.memory_bytes;
  cell.memory_model_bytes = r.memory_model_bytes;
  cell.device = r.device;
  if (first_round) {
    cell.error = compare_pixels(r.image, c.capture.reference);
    cell.config.buffer = rs.config;
    static_cast<TechniqueChoice&>(cell.config) = rs;
    if (uses_table(t.technique)) cell.config.buffer.table = f.table;
    cell.offsets = rs.offsets;
  }
  return r.device;
}

void add_bench_notes(ResultTable& table) {
  table.title = "bench";
  table.notes["times"] =
      "median over repeats of the steady frame: the second frame of one view on the buffers the first made "
      "(gather: insertion; resolve: sort and composite; total: both); first_frame_ms: the first frame's total";
  table.notes["clear_ms"] =
      "GPU path: the buffers' reset before the gather, timed apart from it; CPU path: 0, the reset (a memset of "
      "the kept container) is in the gather; Vulkan path: 0, the reset is in its build (gather_ms)";
  table.notes["insert_order"] = "the order the CPU path's HA-buffer inserted in (auto resolved); others: arrival";
  table.notes["psnr"] = "against the exact reference (SPEC 7 in double precision); identical images: inf (null in JSON)";
  table.notes["floors"] =
      "atomic: one atomic add per fragment; blend: unsorted blending; exact (CPU path): bucket by pixel, sort each "
      "pixel, composite from the buckets (the least an exact technique does; bucketing on one thread); measured in "
      "every round; none on the Vulkan path (neither floor is its device's)";
}

void add_model_notes(ResultTable& table) {
  table.notes["model"] =
      "model_*: the GPU traffic model (docs/performance.md, GPU traffic model): the captured frame replayed in warps of "
      "32 through the technique's shared GLSL; per pass (gather, sort, resolve) the distinct 32-byte sectors and "
      "128-byte lines of each warp instruction, lane atomics, same-address conflicts in an instruction, and the "
      "warps' dependent-load chains, summed; model_*_ms: " + GpuCostModel::h100().source;
}

}  // namespace

ResultTable run_bench(const BenchSettings& s) {
  validate_bench(s);
  std::vector<Case> cases = make_cases(s);
  std::vector<std::vector<Cell3>> cells(cases.size(), std::vector<Cell3>(s.techniques.size()));
  const std::uint64_t total = std::uint64_t{s.repeats} * cases.size() * (s.techniques.size() + (s.floors ? 1 : 0));
  std::uint64_t done = 0;
  ResultTable table;
  warn_empty_scenes(s, cases, table);
  // Rounds outermost: every technique is measured once before any twice, so
  // the machine's drift spreads over all of them alike.
  for (std::uint32_t round = 0; round < s.repeats; ++round)
    for (std::size_t ci = 0; ci < cases.size(); ++ci) {
      Case& c = cases[ci];
      if (c.floors) {
        const Floors f = c.floors->measure();
        c.atomic_ms.push_back(f.atomic_ms);
        c.blend_ms.push_back(f.blend_ms);
        c.exact_ms.push_back(f.exact_ms);
        if (s.on_progress) s.on_progress(++done, total);
      }
      for (std::size_t ti = 0; ti < s.techniques.size(); ++ti) {
        if (bench_cell_applies(s.techniques[ti], c.workload->spec()))
          table.provenance.renderer = measure_cell(s, s.techniques[ti], c, round == 0, cells[ci][ti]);
        if (s.on_progress) s.on_progress(++done, total);
      }
    }
  add_bench_notes(table);
  // The GPU model's replays, one task per row it covers (each on its own copy of the frame's buffers).
  const std::size_t techniques = s.techniques.size();
  std::vector<std::optional<GpuTraffic>> traffic(cases.size() * techniques);
  if (s.model_gpu) {
    add_model_notes(table);
    fork_join(static_cast<std::uint32_t>(traffic.size()), [&](std::uint32_t i) {
      const std::size_t ci = i / techniques, ti = i % techniques;
      if (gpu_model_covers(s.techniques[ti].technique) && bench_cell_applies(s.techniques[ti], cases[ci].workload->spec()))
        traffic[i] = model_gpu_frame(cells[ci][ti].config, cells[ci][ti].offsets, cases[ci].capture.stream);
    });
  }
  for (std::size_t ci = 0; ci < cases.size(); ++ci)
    for (std::size_t ti = 0; ti < techniques; ++ti)
      if (bench_cell_applies(s.techniques[ti], cases[ci].workload->spec()))
        table.rows.push_back(make_row(s, s.techniques[ti], cases[ci], cells[ci][ti], traffic[ci * techniques + ti]));
  return table;
}

}  // namespace habuffer::harness
