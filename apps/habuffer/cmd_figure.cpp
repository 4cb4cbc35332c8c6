// habuffer figure: the papers' figures and the speed-accuracy frontier as
// presets of the harness (harness/figures.h, harness/frontier.h).
#include <cstdio>

#include "commands.h"
#include "harness_cli.h"
#include "habuffer/harness/figures.h"
#include "habuffer/harness/frontier.h"
#include "habuffer/number_text.h"
#include "habuffer/option_rules.h"
#include "habuffer/progress.h"
#include "habuffer/scene_catalog.h"

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
  s.threads = args.u32("threads", 0, 0, kMaxThreads);
  if (name != "table1") args.refuse_unless(s.path == RenderPath::Cpu, {"threads"}, "with --path gl (the GPU inserts)");
  if (args.has("tau")) s.tau = usage_errors("tau", [&] { return parse_cull_threshold(args.str("tau", "")); });
  const auto allowed = [&](std::initializer_list<const char*> own) {
    for (const char* o : {"scene", "scenes", "opacities", "frames", "load", "planes", "fragments", "loads", "picks",
                          "targets", "no-allocate"}) {
      bool mine = false;
      for (const char* m : own) mine |= std::string(m) == o;
      if (!mine && args.has(o)) throw UsageError("option --" + std::string(o) + " does not apply to figure " + name);
    }
  };
  args.refuse_unless(args.has("picks"), {"targets"}, "without --picks (the targets choose the picks)");
  harness::ResultTable table;
  ProgressBar progress = ProgressBar::for_terminal("habuffer figure " + name, "runs", args.has("quiet"));
  s.on_progress = progress.callback();
  // Every file and value is checked before the first render.
  HarnessOutputs outputs;
  if (name == "table1") {
    allowed({"fragments", "loads", "no-allocate"});
    args.refuse_unless(false, {"path", "repeats", "threads", "tau"}, "on table1 (sizes only, nothing is rendered)");
    const std::vector<Extent> size = parse_sizes(args, "1024x1024");
    if (size.size() != 1) throw UsageError("--size takes one WxH for table1");
    std::vector<std::uint64_t> counts;
    for (const std::string& f : args.list("fragments", "850000,1500000,10000000"))
      counts.push_back(usage_errors("fragments", [&] { return parse_unsigned(f, 1, harness::kMaxTableFragments); }));
    std::vector<double> loads;
    for (const std::string& l : args.list("loads", "0.9,0.8,0.5"))
      loads.push_back(usage_errors("loads", [&] { return parse_load_factor(l); }));
    usage_errors("", [&] { harness::validate_memory_table(size[0], counts, loads); });
    outputs = parse_outputs(args, {});
    table = harness::run_memory_table(size[0], counts, loads, !args.has("no-allocate"));
  } else {
    const std::vector<Extent> sizes = parse_sizes(args, "256x256");
    s.size = sizes.at(0);
    if (sizes.size() != 1 && name != "frontier") throw UsageError("--size takes one WxH for figure " + name);
    if (name == "fig2") {
      allowed({"scene", "opacities"});
      const std::vector<harness::WorkloadSpec> scene = parse_scenes_or(args, "scene", "hairball");
      if (scene.size() != 1) throw UsageError("--scene takes one scene for fig2");
      usage_errors("", [&] { harness::check_fig2_scene(scene[0]); });
      std::vector<float> opacities;
      SceneOptions probe;  // each opacity by the scene option's rule
      for (const std::string& o : args.list("opacities", "0.125,0.25,0.5,1")) {
        usage_errors("opacities", [&] { set_scene_option(probe, "opacity", o); });
        opacities.push_back(probe.opacity);
      }
      outputs = parse_outputs(args, scene);
      const auto context = context_for(true, "figure");
      table = harness::run_fig2(scene[0], opacities, s);
    } else if (name == "fig8") {
      allowed({"scene", "frames", "load"});
      const std::vector<harness::WorkloadSpec> scene = parse_scenes_or(args, "scene", "quads:count=64");
      if (scene.size() != 1) throw UsageError("--scene takes one scene for fig8");
      usage_errors("", [&] { harness::check_fig8_scene(scene[0]); });
      const std::uint32_t frames = args.u32("frames", 16, 2, 100000);
      double load = 0.64;
      if (args.has("load")) load = usage_errors("load", [&] { return parse_load_factor(args.str("load", "")); });
      outputs = parse_outputs(args, scene);
      const auto context = context_for(true, "figure");
      table = harness::run_fig8(scene[0], frames, load, s);
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
      usage_errors("", [&] { harness::validate_bench(b); });
      const std::vector<double> targets =
          args.has("picks") ? parse_reals(args, "targets", "30,40,50", 0.0, 1000.0) : std::vector<double>{};
      outputs = parse_outputs(args, b.scenes);
      const auto context = context_for(true, "figure");
      table = harness::run_bench(b);
      table.title = name;
      if (name == "frontier") {
        harness::mark_pareto(table);
        if (!outputs.picks.empty()) {
          harness::ResultTable p = harness::frontier_picks(table, targets);
          write_outputs(("figure " + name).c_str(), p, outputs.picks, argv);
        }
      }
    } else {
      throw UsageError("unknown figure '" + name + "' (fig2, fig8, fig10, table1, frontier)");
    }
  }
  write_outputs(("figure " + name).c_str(), table, outputs.out, rest);
  return 0;
}

}  // namespace habuffer::cli
