#include "habuffer/harness/figures.h"
#include "habuffer/technique_descriptor.h"

#include <cmath>
#include <stdexcept>

#include "habuffer/harness/technique_spec.h"
#include "habuffer/lossless_build.h"
#include "habuffer/memory_model.h"

namespace habuffer::harness {
namespace {

RenderSettings base_settings(const FigureSettings& s, Extent size) {
  RenderSettings r;
  r.path = s.path;
  r.threads = s.threads;
  r.config.screen = size;
  return r;
}

void tick(const FigureSettings& s, std::uint64_t& done, std::uint64_t total) {
  if (s.on_progress) s.on_progress(++done, total);
}

// A fixed table, so no frame regathers and the time is one gather: load 0.5
// of the fragments, or the screen when they are too few for that.
Extent fixed_table(Extent screen, std::uint64_t fragments) {
  return fragments >= screen.area() / 2 ? table_for_load(screen, fragments, 0.5) : screen;
}

std::string tau_text(float tau) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", static_cast<double>(tau));
  return buf;
}

// Seed 000's Fig. 2 measures frames with and without translucent shadows:
// a directional light from above, its map the screen's size, its buffer
// culled like the view's, table automatic (grown until nothing is dropped).
ShadowSettings fig2_light(Extent size, float tau) {
  ShadowSettings l;
  l.light.orthographic = true;
  l.light.direction = {-0.4f, -1.0f, -0.3f};
  l.light.size = size;
  l.early_cull_tau = tau;
  return l;
}

// The frame with and without shadows: the second of two frames of one view
// (the first pays the counting pass and the light buffer's one build),
// interleaved repeat by repeat.
struct ShadowColumns {
  std::vector<double> plain_ms, shadowed_ms;
  LightStats light;
};

ShadowColumns shadow_columns(const Workload& workload, const RenderSettings& plain, const FigureSettings& s,
                             std::uint64_t& done, std::uint64_t total) {
  ShadowColumns c;
  for (std::uint32_t rep = 0; rep < s.repeats; ++rep) {
    RenderSettings r = plain;
    r.frames = 2;
    c.plain_ms.push_back(workload.render(r).frames.back().frame_ms);
    r.shadows = fig2_light(s.size, plain.config.early_cull_tau);
    const RenderResult shadowed = workload.render(r);
    c.shadowed_ms.push_back(shadowed.frames.back().frame_ms);
    c.light = *shadowed.light;
    tick(s, done, total);
  }
  return c;
}

}  // namespace

void check_fig2_scene(const WorkloadSpec& scene) {
  if (!scene.fragments.empty())
    throw std::invalid_argument("fig2 sets the scene's opacity: '" + scene.word + "' is a fragment file (its colours are fixed)");
  if (scene.keys.count("opacity") != 0)
    throw std::invalid_argument("fig2 sets the opacity from --opacities: drop opacity= from '" + scene.word + "'");
}

void check_fig8_scene(const WorkloadSpec& scene) {
  if (!scene.fragments.empty() || !scene_takes(scene.scene, "spread"))
    throw std::invalid_argument("fig8 pulls the quads together by their spread: '" + scene.word + "' has none (" +
                                scenes_taking_text("spread") + ")");
  if (scene.keys.count("spread") != 0)
    throw std::invalid_argument("fig8 sets the spread per frame: drop spread= from '" + scene.word + "'");
}

namespace {

// Fig. 2's frame-time columns without and with translucent shadows, and the light's.
void set_shadow_columns(ResultRow& row, const ShadowColumns& sc, const FrameStats& last) {
  const Spread plain = spread_of(sc.plain_ms), shadowed = spread_of(sc.shadowed_ms);
  row.set("frame_ms", plain.median).set("frame_ms_shadows", shadowed.median)
      .set("fps", plain.median > 0 ? 1e3 / plain.median : 0.0)
      .set("fps_shadows", shadowed.median > 0 ? 1e3 / shadowed.median : 0.0)
      .set("shadow_frame_ratio", shadowed.median > 0 ? plain.median / shadowed.median : 0.0)
      .set("light_fragments", sc.light.counters.fragments).set("light_stored", sc.light.counters.stored())
      .set("fragments_with_shadows", last.counters.fragments + sc.light.counters.fragments)
      .set("light_build_ms", sc.light.build_ms).set("light_builds", sc.light.builds);
}

void add_fig2_notes(ResultTable& table, const WorkloadSpec& scene, const FigureSettings& s) {
  table.notes["workload"] = scene.word + " at " + s.size.str() + ", opacity-1 meshes inserted (not the opaque pass)";
  table.notes["frame_ms"] = "the second of two frames of one view, without and with translucent shadows "
                            "(frame_ms_shadows), interleaved; fps = 1000 / frame_ms";
  table.notes["shadow_frame_ratio"] = "fps_shadows / fps (seed 000's Fig. 2 on a GTX 680: 0.63 to 0.71)";
  table.notes["light"] = "directional (-0.4, -1, -0.3), map " + s.size.str() +
                         ", its buffer culled like the view's, table automatic; built once before the first frame "
                         "(light_build_ms), so frame_ms_shadows holds only the lookups";
  table.notes["table"] = "fixed, sized for load 0.5 of the fragments without cull (the screen when they are fewer)";
  table.notes["fill_rate_mfrag_per_s"] = "fragments reaching insertion per second of gather (seed 000: stays constant)";
}

}  // namespace

ResultTable run_fig2(const WorkloadSpec& scene, const std::vector<float>& opacities, const FigureSettings& s) {
  check_fig2_scene(scene);
  if (opacities.empty()) throw std::invalid_argument("no opacity given");
  ResultTable table;
  table.title = "fig2";
  const std::uint64_t total = opacities.size() * 2ull * s.repeats * 2;
  std::uint64_t done = 0;
  for (const float opacity : opacities) {
    WorkloadSpec w = scene;
    w.options.opacity = opacity;
    w.options.insert_opaque = true;  // opacity 1 through the A-buffer, as the paper measures it
    const Workload workload(w, s.size);
    const ExactCapture capture = workload.capture();
    for (const float tau : {0.0f, s.tau}) {
      std::vector<double> gather;
      FrameStats last;
      std::string device;
      RenderSettings r = base_settings(s, s.size);
      TechniqueSpec t;
      t.cull = tau;
      t.apply(r, capture.fragments);
      r.config.table = fixed_table(s.size, capture.fragments);
      for (std::uint32_t rep = 0; rep < s.repeats; ++rep) {
        const RenderResult res = workload.render(r);
        last = res.frames.back();
        gather.push_back(last.gather_ms);
        device = res.device;
        tick(s, done, total);
      }
      const Spread g = spread_of(gather);
      const double frags = static_cast<double>(last.counters.fragments);
      ResultRow row;
      row.set("opacity", static_cast<double>(opacity)).set("early_cull", tau > 0 ? tau_text(tau) : std::string("off"));
      set_counters(row, last.counters);
      row.set("gather_ms", g.median).set("gather_ms_min", g.min).set("gather_ms_max", g.max)
          .set("fill_rate_mfrag_per_s", g.median > 0 ? frags / (g.median * 1e3) : 0.0)
          .set("stored_mfrag_per_s", g.median > 0 ? static_cast<double>(last.counters.stored()) / (g.median * 1e3) : 0.0)
          .set("max_age", last.max_age);
      set_shadow_columns(row, shadow_columns(workload, r, s, done, total), last);
      table.rows.push_back(row);
      table.provenance.renderer = device;
    }
  }
  add_fig2_notes(table, scene, s);
  return table;
}

ResultTable run_fig8(const WorkloadSpec& quads, std::uint32_t frames, double load, const FigureSettings& s) {
  check_fig8_scene(quads);
  if (frames < 2) throw std::invalid_argument("fig8 needs at least 2 frames (spread 1 down to 0)");
  ResultTable table;
  table.title = "fig8";
  std::optional<Extent> fixed;
  const std::uint64_t total = std::uint64_t{frames} * 2;
  std::uint64_t done = 0;
  for (std::uint32_t k = 0; k < frames; ++k) {
    WorkloadSpec w = quads;
    w.options.spread = 1.0f - static_cast<float>(k) / static_cast<float>(frames - 1);
    const Workload workload(w, s.size);
    if (!fixed) fixed = table_for_load(s.size, workload.capture().fragments, load);
    for (const float tau : {0.0f, s.tau}) {
      RenderSettings r = base_settings(s, s.size);
      r.config.table = *fixed;
      r.config.early_cull_tau = tau;
      const RenderResult res = workload.render(r);
      const FrameStats& f = res.frames.back();
      ResultRow row;
      row.set("frame", k).set("spread", static_cast<double>(w.options.spread))
          .set("early_cull", tau > 0 ? tau_text(tau) : std::string("off")).set("table", f.table.str());
      set_counters(row, f.counters);
      row.set("gather_ms", f.gather_ms).set("resolve_ms", f.resolve_ms)
          .set("max_age", f.max_age).set("load_factor", f.load_factor);
      table.rows.push_back(row);
      table.provenance.renderer = res.device;
      tick(s, done, total);
    }
  }
  table.notes["workload"] = quads.word + " at " + s.size.str() + ", spread 1 (anywhere) to 0 (stacked exactly)";
  table.notes["table"] = "fixed for every frame, sized for load " + std::to_string(load) + " of frame 0's fragments";
  return table;
}

BenchSettings fig10_bench_settings(std::uint32_t planes, const FigureSettings& s) {
  BenchSettings b;
  b.path = s.path;
  b.repeats = s.repeats;
  b.threads = s.threads;
  b.sizes = {s.size};
  b.floors = false;
  for (const char* order : {"front", "back"})
    b.scenes.push_back(parse_workload_spec("planes:order=" + std::string(order) + ":count=" + std::to_string(planes)));
  const std::string tau = tau_text(s.tau);
  for (const char* t : {"ha", "sorted-lists"})
    for (const std::string& knobs : {std::string(), ":cull=" + tau, ":cull=" + tau + ":sat"})
      b.techniques.push_back(parse_technique_spec(t + knobs));
  return b;
}

void validate_memory_table(Extent screen, const std::vector<std::uint64_t>& fragment_counts,
                           const std::vector<double>& loads) {
  if (screen.area() == 0) throw std::invalid_argument("--size " + screen.str() + " is empty");
  if (fragment_counts.empty() || loads.empty()) throw std::invalid_argument("table1 needs fragment counts and loads");
  for (const double l : loads)
    if (!(l > 0.0 && l <= 1.0)) throw std::invalid_argument("--loads: " + tau_text(static_cast<float>(l)) + " is not in (0, 1]");
  for (const std::uint64_t f : fragment_counts) {
    if (f == 0 || f > kMaxTableFragments)
      throw std::invalid_argument("--fragments: " + std::to_string(f) + " outside 1.." + std::to_string(kMaxTableFragments));
    for (const double l : loads)
      if (!(static_cast<double>(f) / l <= static_cast<double>(UINT32_MAX)))
        throw std::invalid_argument("--loads: load " + tau_text(static_cast<float>(l)) + " of " + std::to_string(f) +
                                    " fragments needs more than 2^32 - 1 slots: raise the load");
  }
}

ResultTable run_memory_table(Extent screen, const std::vector<std::uint64_t>& fragment_counts,
                             const std::vector<double>& loads, bool allocate) {
  validate_memory_table(screen, fragment_counts, loads);
  // Seed 000's Table 1 (MiB, V = 1024^2) for F = 0.85 M, 1.5 M, 10 M, where it has the row.
  struct Published {
    std::string row;
    double mib[3];
  };
  const std::vector<Published> published{{"linked-list", {12.9, 19.7, 108.9}},
                                         {"ha:load=0.9", {7.2, 12.7, 84.8}},
                                         {"ha:load=0.8", {8.1, 14.3, 95.4}},
                                         {"ha:load=0.5", {13.0, 22.9, 152.6}}};
  const std::vector<std::uint64_t> paper_counts{850000, 1500000, 10000000};
  const double mib = 1024.0 * 1024.0;
  ResultTable table;
  table.title = "table1";
  auto published_value = [&](const std::string& row, std::uint64_t f) -> std::optional<double> {
    if (screen.area() != 1024ull * 1024ull) return std::nullopt;
    for (std::size_t i = 0; i < paper_counts.size(); ++i)
      if (paper_counts[i] == f)
        for (const Published& p : published)
          if (p.row == row) return p.mib[i];
    return std::nullopt;
  };
  for (const std::uint64_t f : fragment_counts) {
    std::vector<TechniqueSpec> specs;
    for (const double l : loads) {
      TechniqueSpec t;
      t.load = l;
      specs.push_back(t);
    }
    for (const char* w : {"lists", "paged-lists", "sorted-lists", "arrays:k=16", "kbuffer:k=8", "wboit", "blend"})
      specs.push_back(parse_technique_spec(w));
    for (const TechniqueSpec& t : specs) {
      TechniqueConfig c;
      c.technique = t.technique;
      c.buffer.screen = screen;
      // Seed 000 sizes the table as F / L slots even below the screen, which
      // SPEC 1's geometry rule forbids: such rows get the model, not an allocation.
      bool allocatable = true;
      c.buffer.table = screen;
      if (t.load) try {
          c.buffer.table = table_for_load(screen, f, *t.load);
        } catch (const std::invalid_argument&) {
          allocatable = false;
        }
      c.layers = t.layers.value_or(HABUFFER_DEFAULT_LAYERS);
      const std::uint64_t capacity = uses_table(t.technique) ? (allocatable ? c.buffer.table.area()
                                                                            : capacity_for_load(f, *t.load))
                                     : uses_pool(t.technique) ? f
                                                              : 0;
      c.pool_capacity = uses_pool(t.technique) ? f : screen.area();
      ResultRow row;
      row.set("technique", t.label()).set("fragments", f).set("pixels", screen.area());
      row.set("paper_formula_mib", paper_memory_bytes(t.technique, screen.area(), f, t.load.value_or(1.0), c.layers) / mib);
      const std::uint64_t model = memory_model_bytes(c, capacity);
      row.set("model_mib", static_cast<double>(model) / mib);
      const bool affordable = model <= kMaxTableAllocationBytes;
      if (allocate && allocatable && affordable) {
        const std::unique_ptr<FragmentBuffer> b = make_fragment_buffer(c, OffsetSource{});
        row.set("allocated_mib", static_cast<double>(b->memory_bytes()) / mib);
      }
      if (!allocatable) row.set("note", "table of F/L slots is below the screen (SPEC 1): model only");
      else if (allocate && !affordable)
        row.set("note", "model only: more than the " + std::to_string(kMaxTableAllocationBytes >> 30) +
                            " GiB table1 allocates");
      const std::string_view named_row = descriptor(t.technique).paper_memory_row;
      const std::string paper_row = named_row.empty() ? t.label() : std::string(named_row);
      if (const std::optional<double> p = published_value(paper_row, f)) row.set("paper_table_mib", *p);
      table.rows.push_back(row);
    }
  }
  table.notes["paper_formula_mib"] = "seed 000's formulas (56-bit fragments, 32-bit pointers, max-age byte per 8x8)";
  table.notes["model_mib"] = "our record sizes (memory_model.h), what the CPU containers allocate";
  table.notes["paper_table_mib"] = "the values printed in seed 000's Table 1 (V = 1024^2), where it has the row";
  table.provenance.renderer = "none (sizes only)";
  return table;
}

}  // namespace habuffer::harness
