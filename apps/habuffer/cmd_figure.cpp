// habuffer figure: the papers' figures and the speed-accuracy frontier as
// presets of the harness (harness/figures.h, harness/frontier.h).
#include <cstdio>

#include "commands.h"
#include "harness_cli.h"
#include "habuffer/harness/figures.h"
#include "habuffer/harness/frontier.h"
#include "habuffer/progress.h"

namespace habuffer::cli {
namespace {

constexpr const char* kHelp =
    "usage: habuffer figure fig2|fig8|fig10|table1|frontier --out F.json[,F.csv] [--size WxH (256x256)]\n"
    "         [--path gl|cpu] [--repeats N (3)] [--threads N] [--tau T (0.99)] [--quiet]\n"
    "  fig2      seed 000 Fig. 2: early cull vs opacity, [--scene S (hairball)] [--opacities A,.. (0.125,0.25,0.5,1)];\n"
    "            stored fragments, gather time and fill rate with and without cull (opacity 1 inserted)\n"
    "  fig8      seed 000 Fig. 8: quads pulled together over [--frames N (16)] frames into a table fixed at\n"
    "            [--load L (0.64)], [--scene S (quads:count=64)]; time and max age per frame, with and without cull\n"
    "  fig10     seed 001 Fig. 10: [--planes N (32)] planes front to back and back to front, ha and sorted-lists,\n"
    "            exact, with cull, with cull and saturation\n"
    "  table1    seed 000 Table 1: memory by formula, our model and allocated, at [--fragments F,.. (850000,\n"
    "            1500000,10000000)] and [--loads L,.. (0.9,0.8,0.5)] on --size (default here 1024x1024);\n"
    "            [--no-allocate] skips the allocation\n"
    "  frontier  techniques and knobs on [--scenes S,.. (engine,hairball)]: time, memory and psnr, Pareto rows\n"
    "            marked; [--picks F.json[,F.csv]] the fastest configuration at [--targets DB,.. (30,40,50)]\n";

}  // namespace

int run_figure(const std::vector<std::string>& argv) {
  if (print_help(argv, kHelp) || argv.empty()) {
    if (argv.empty()) throw UsageError("name a figure: fig2, fig8, fig10, table1 or frontier");
    return 0;
  }
  const std::string name = argv[0];
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  const Args args(rest,
                  {"out", "size", "path", "repeats", "threads", "tau", "scene", "scenes", "opacities", "frames", "load",
                   "planes", "fragments", "loads", "picks", "targets"},
                  {"quiet", "no-allocate"});
  harness::FigureSettings s;
  s.path = parse_path(args);
  s.repeats = args.u32("repeats", 3, 1, 1000);
  s.threads = args.u32("threads", 0);
  s.tau = args.f32("tau", 0.99f);
  if (!(s.tau > 0.0f && s.tau <= 1.0f)) throw UsageError("--tau must be in (0, 1]");
  const auto allowed = [&](std::initializer_list<const char*> own) {
    for (const char* o : {"scene", "scenes", "opacities", "frames", "load", "planes", "fragments", "loads", "picks",
                          "targets", "no-allocate"}) {
      bool mine = false;
      for (const char* m : own) mine |= std::string(m) == o;
      if (!mine && args.has(o)) throw UsageError("option --" + std::string(o) + " does not apply to figure " + name);
    }
  };
  std::vector<std::string> outputs;
  harness::ResultTable table;
  ProgressBar progress = ProgressBar::for_terminal("habuffer figure " + name, "runs", args.has("quiet"));
  s.on_progress = progress.callback();
  if (name == "table1") {
    allowed({"fragments", "loads", "no-allocate"});
    const std::vector<Extent> size = parse_sizes(args, "1024x1024");
    std::vector<std::uint64_t> counts;
    for (const double f : parse_reals(args, "fragments", "850000,1500000,10000000")) {
      if (!(f >= 1.0) || f != std::floor(f)) throw UsageError("--fragments: counts must be positive integers");
      counts.push_back(static_cast<std::uint64_t>(f));
    }
    outputs = parse_outputs(args, {});
    try {
      table = harness::run_memory_table(size.at(0), counts, parse_reals(args, "loads", "0.9,0.8,0.5"), !args.has("no-allocate"));
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  } else {
    const std::vector<Extent> sizes = parse_sizes(args, "256x256");
    s.size = sizes.at(0);
    if (name == "fig2") {
      allowed({"scene", "opacities"});
      const std::vector<harness::WorkloadSpec> scene = parse_scenes_or(args, "scene", "hairball");
      std::vector<float> opacities;
      for (const double o : parse_reals(args, "opacities", "0.125,0.25,0.5,1")) opacities.push_back(static_cast<float>(o));
      outputs = parse_outputs(args, {});
      const auto context = context_for(true, "figure");
      table = harness::run_fig2(scene.at(0), opacities, s);
    } else if (name == "fig8") {
      allowed({"scene", "frames", "load"});
      const std::vector<harness::WorkloadSpec> scene = parse_scenes_or(args, "scene", "quads:count=64");
      const std::uint32_t frames = args.u32("frames", 16, 2, 100000);
      const double load = args.real("load", 0.64);
      if (!(load > 0.0 && load <= 1.0)) throw UsageError("--load must be in (0, 1]");
      outputs = parse_outputs(args, {});
      const auto context = context_for(true, "figure");
      table = harness::run_fig8(scene.at(0), frames, load, s);
    } else if (name == "fig10" || name == "frontier") {
      harness::BenchSettings b;
      if (name == "fig10") {
        allowed({"planes"});
        b = harness::fig10_bench_settings(args.u32("planes", 32, 1, 4096), s);
      } else {
        allowed({"scenes", "picks", "targets"});
        b.path = s.path;
        b.repeats = s.repeats;
        b.threads = s.threads;
        b.sizes = sizes;
        b.scenes = parse_scenes_or(args, "scenes", "engine,hairball");
        b.techniques = harness::frontier_techniques(s.path);
      }
      b.on_progress = s.on_progress;
      outputs = parse_outputs(args, {});
      std::vector<std::string> picks;
      if (args.has("picks")) {
        picks = args.list("picks", "");
        harness::check_table_paths(picks);
      }
      const auto context = context_for(true, "figure");
      table = harness::run_bench(b);
      table.title = name;
      if (name == "frontier") {
        harness::mark_pareto(table);
        if (!picks.empty()) {
          harness::ResultTable p = harness::frontier_picks(table, parse_reals(args, "targets", "30,40,50"));
          write_outputs(("figure " + name).c_str(), p, picks, argv);
        }
      }
    } else {
      throw UsageError("unknown figure '" + name + "' (fig2, fig8, fig10, table1, frontier)");
    }
  }
  write_outputs(("figure " + name).c_str(), table, outputs, rest);
  return 0;
}

}  // namespace habuffer::cli
