// habuffer figure: the papers' figures and the speed-accuracy frontier as
// presets of the harness (harness/figures.h, harness/frontier.h).
#include <algorithm>
#include <cstdio>

#include "commands.h"
#include "file_values.h"
#include "harness_cli.h"
#include "habuffer/harness/figures.h"
#include "habuffer/harness/frontier.h"
#include "habuffer/harness/shadow_frontier.h"
#include "habuffer/harness/voxel_figure.h"
#include "habuffer/csg.h"
#include "habuffer/harness/csg_figure.h"
#include "habuffer/number_text.h"
#include "habuffer/option_rules.h"
#include "habuffer/progress.h"
#include "habuffer/scene_catalog.h"

namespace habuffer::cli {
namespace {

// What a figure's run reads and writes: its options, the settings every
// figure shares, its outputs, and the command line (for a second table).
struct FigureRun {
  const Args& args;
  harness::FigureSettings& s;
  HarnessOutputs outputs;
  const std::vector<std::string>& argv;
};

// One figure: its name, what it draws, its own options and its run.
struct Figure {
  std::string name;
  std::string what;  ///< one or two help lines, "  " indented, each ending in "\n"
  std::vector<OptionSpec> own;
  harness::ResultTable (*run)(FigureRun& r);
};

// Every figure's options (--size 256x256 but table1's, as the paper's screen).
std::vector<OptionSpec> figure_common(bool table1) {
  std::vector<OptionSpec> common = harness_options({"out"});
  if (table1)
    common.push_back({"size", "WxH", "1024x1024", "the screen (the paper's Table 1 sizes 1024x1024)"});
  else
    common = common + harness_options({"size"});
  return common + harness_options({"path", "repeats", "threads"}) +
         std::vector<OptionSpec>{{"tau", "T", "0.99", "early cull's threshold in the runs with cull"}} +
         harness_options({"quiet"});
}

// --size, one WxH but for the frontier, into `s`.
std::vector<Extent> figure_sizes(const Args& args, harness::FigureSettings& s, const std::string& name) {
  const std::vector<Extent> sizes = parse_sizes(args);
  s.size = sizes.at(0);
  if (sizes.size() != 1 && name != "frontier") throw UsageError("--size takes one WxH for figure " + name);
  return sizes;
}

// --scene, one scene word, checked by `check`.
harness::WorkloadSpec one_scene(const Args& args, void (*check)(const harness::WorkloadSpec&)) {
  const harness::WorkloadSpec scene = parse_scene(args, "scene");
  usage_errors("", [&] { check(scene); });
  return scene;
}

harness::ResultTable run_fig2(FigureRun& r) {
  figure_sizes(r.args, r.s, "fig2");
  const harness::WorkloadSpec scene = one_scene(r.args, harness::check_fig2_scene);
  std::vector<float> opacities;
  SceneOptions probe;  // each opacity by the scene option's rule
  for (const std::string& o : r.args.list("opacities")) {
    usage_errors("opacities", [&] { set_scene_option(probe, "opacity", o); });
    opacities.push_back(probe.opacity);
  }
  r.outputs = parse_outputs(r.args);
  const auto context = context_for(true, "figure");
  return harness::run_fig2(scene, opacities, r.s);
}

harness::ResultTable run_fig8(FigureRun& r) {
  figure_sizes(r.args, r.s, "fig8");
  const harness::WorkloadSpec scene = one_scene(r.args, harness::check_fig8_scene);
  const std::uint32_t frames = r.args.u32_in("frames", 2, 100000);
  const double load = usage_errors("load", [&] { return parse_load_factor(r.args.str("load")); });
  r.outputs = parse_outputs(r.args);
  const auto context = context_for(true, "figure");
  return harness::run_fig8(scene, frames, load, r.s);
}

// fig10 and the frontier: bench presets.
harness::ResultTable run_bench_figure(FigureRun& r, const std::string& name, harness::BenchSettings b) {
  b.on_progress = r.s.on_progress;
  usage_errors("", [&] { harness::validate_bench(b); });
  const std::vector<double> targets =
      r.args.has("picks") ? parse_reals(r.args, "targets", 0.0, 1000.0) : std::vector<double>{};
  // Every target is picked without a budget, then within each budget.
  std::vector<double> budgets{harness::kNoMemoryBudget};
  if (r.args.has("picks"))
    for (const double budget : parse_reals(r.args, "memory-budgets", 0.0, 1e9)) budgets.push_back(budget);
  r.outputs = parse_outputs(r.args);
  const auto context = context_for(true, "figure");
  harness::ResultTable table = harness::run_bench(b);
  table.title = name;
  if (name == "frontier") {
    harness::mark_pareto(table);
    if (!r.outputs.picks.empty()) {
      harness::ResultTable p = harness::frontier_picks(table, targets, budgets);
      write_outputs(("figure " + name).c_str(), p, r.outputs.picks, r.argv);
    }
  }
  return table;
}

harness::ResultTable run_fig10(FigureRun& r) {
  figure_sizes(r.args, r.s, "fig10");
  return run_bench_figure(r, "fig10", harness::fig10_bench_settings(r.args.u32_in("planes", 1, 4096), r.s));
}

harness::ResultTable run_frontier(FigureRun& r) {
  harness::BenchSettings b;
  b.sizes = figure_sizes(r.args, r.s, "frontier");
  b.path = r.s.path;
  b.repeats = r.s.repeats;
  b.threads = r.s.threads;
  b.scenes = parse_scenes(r.args, "scenes");
  b.techniques = harness::frontier_techniques(r.s.path);
  return run_bench_figure(r, "frontier", b);
}

harness::ResultTable run_shadows(FigureRun& r) {
  r.args.refuse_unless(false, {"path", "tau"},
                       "on figure shadows (the light pass runs on gl; its other light buffers are built on the cpu)");
  figure_sizes(r.args, r.s, "shadows");
  const harness::WorkloadSpec scene = parse_scene(r.args, "scene");
  if (!scene.fragments.empty())
    throw UsageError("option --scene: the shadow frontier lights a scene, not a fragment file");
  harness::ShadowFrontierSettings f;
  f.size = r.s.size;
  f.light_size = r.args.size("light-size");
  f.repeats = r.s.repeats;
  f.threads = r.s.threads;
  f.max_receivers = r.args.u64_in("receivers");
  f.on_progress = r.s.on_progress;
  r.outputs = parse_outputs(r.args);
  const auto context = context_for(true, "figure");
  return harness::run_shadow_frontier(scene, f);
}

// A comma list of counts in 1..most (--grids, --cylinders).
std::vector<std::uint32_t> counts(const Args& args, const char* option, std::uint32_t most) {
  std::vector<std::uint32_t> out;
  for (const std::string& item : args.list(option))
    out.push_back(usage_errors(option, [&] {
      std::size_t used = 0;
      unsigned long n = 0;
      try {
        n = std::stoul(item, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != item.size() || n == 0 || n > most)
        throw std::invalid_argument("'" + item + "' is not a count in 1.." + std::to_string(most));
      return static_cast<std::uint32_t>(n);
    }));
  return out;
}

harness::ResultTable run_voxels(FigureRun& r) {
  r.args.refuse_unless(false, {"size"}, "on figure voxels (--grids sets the sizes)");
  r.args.refuse_unless(false, {"tau"}, "on figure voxels (nothing is culled: a solid needs every crossing)");
  harness::VoxelFigureSettings f;
  f.meshes = r.args.list("meshes");
  f.grids = counts(r.args, "grids", 4096);
  const std::string axis = r.args.str("axis");
  if (axis != "x" && axis != "y" && axis != "z") throw UsageError("option --axis: '" + axis + "' is not x, y or z");
  f.axis = axis == "x" ? VoxelAxis::X : axis == "y" ? VoxelAxis::Y : VoxelAxis::Z;
  f.cpu = r.s.path == RenderPath::Cpu;
  f.repeats = r.s.repeats;
  f.on_progress = r.s.on_progress;
  r.outputs = parse_outputs(r.args);
  const auto context = context_for(true, "figure");
  return harness::run_voxel_figure(f);
}

harness::ResultTable run_csg(FigureRun& r) {
  r.args.refuse_unless(false, {"tau"}, "on figure csg (nothing is culled)");
  figure_sizes(r.args, r.s, "csg");
  harness::CsgFigureSettings f;
  f.size = r.s.size;
  f.cpu = r.s.path == RenderPath::Cpu;
  f.repeats = r.s.repeats;
  f.on_progress = r.s.on_progress;
  f.cylinders = counts(r.args, "cylinders", kMaxCsgPrimitives - 1);
  r.outputs = parse_outputs(r.args);
  const auto context = context_for(true, "figure");
  return harness::run_csg_figure(f);
}

harness::ResultTable run_table1(FigureRun& r) {
  r.args.refuse_unless(false, {"path", "repeats", "threads", "tau"}, "on table1 (sizes only, nothing is rendered)");
  const std::vector<Extent> size = parse_sizes(r.args);
  if (size.size() != 1) throw UsageError("--size takes one WxH for table1");
  std::vector<std::uint64_t> counts;
  for (const std::string& f : r.args.list("fragments"))
    counts.push_back(usage_errors("fragments", [&] { return parse_unsigned(f, 1, harness::kMaxTableFragments); }));
  std::vector<double> loads;
  for (const std::string& l : r.args.list("loads"))
    loads.push_back(usage_errors("loads", [&] { return parse_load_factor(l); }));
  usage_errors("", [&] { harness::validate_memory_table(size[0], counts, loads); });
  r.outputs = parse_outputs(r.args);
  return harness::run_memory_table(size[0], counts, loads, !r.args.has("no-allocate"));
}

const std::vector<Figure>& figures() {
  static const std::vector<Figure> list{
      {"fig2", "  seed 000 Fig. 2: early cull vs opacity; stored fragments, gather time and fill rate with and\n"
               "  without cull (opacity 1 inserted); frame time and fragments with and without translucent shadows\n",
       {{"scene", "S", "hairball", "the scene", reads_in(scene_word_file, "{}")}, {"opacities", "A,..", "0.125,0.25,0.5,1", "the opacities"}},
       run_fig2},
      {"fig8", "  seed 000 Fig. 8: quads pulled together over N frames into a table fixed at load L; time and max\n"
               "  age per frame, with and without cull\n",
       {{"scene", "S", "quads:count=64", "the scene", reads_in(scene_word_file, "{}")},
        {"frames", "N", "16", "frames"},
        {"load", "L", "0.64", "the fixed table's load of the first frame"}},
       run_fig8},
      {"fig10", "  seed 001 Fig. 10: N planes front to back and back to front, ha and sorted-lists, exact, with\n"
                "  cull, with cull and saturation\n",
       {{"planes", "N", "32", "planes"}}, run_fig10},
      {"table1", "  seed 000 Table 1: memory by formula, our model and allocated\n",
       {{"fragments", "F,..", "850000,1500000,10000000", "fragment counts (Table 1's)"},
        {"loads", "L,..", "0.9,0.8,0.5", "loads (Table 1's)"},
        {"no-allocate", "", "", "skip the allocation"}},
       run_table1},
      {"frontier", "  techniques and knobs: time, memory and psnr, Pareto rows marked (time, memory, both);\n"
                   "  picks: the fastest per psnr target and memory budget\n",
       {{"scenes", "S,..", "engine,hairball", "the scenes", reads_in(scene_word_files, "{}")},
        {"picks", "F.json[,F.csv]", "", "the fastest configuration at each target", writes_in(listed_files, "{}")},
        {"targets", "DB,..", "30,40,50", "the picks' psnr targets (with --picks)"},
        {"memory-budgets", "B,..", "10,16,32",
         "the picks' memory budgets, bytes per fragment (with --picks; each target is also picked without one)"}},
       run_frontier},
      {"shadows", "  the shadow frontier: light buffers (ha exact and culled, k-buffer, opacity shadow maps) from one\n"
                  "  light pass, RMSE of T against the ray-traced reference vs memory vs build time\n",
       {{"scene", "S", "hairball", "the scene", reads_in(scene_word_file, "{}")},
        {"light-size", "WxH", "512x512", "the light map"},
        {"receivers", "N", "0", "receivers checked, every k-th (0: all)"}},
       run_shadows},
      {"voxels", "  issue 21's voxelization table: meshes x grid sizes, time, lists vs dense bytes, mismatches\n"
                 "  against the ray-parity reference outside its band\n",
       {{"meshes", "M,..", "sphere,torus,wuson,spider", "solids (sphere, torus, box) or scenes", reads_in(mesh_files, "{}")},
        {"grids", "N,..", "128,256,512", "voxels per side"},
        {"axis", "x|y|z", "z", "the views' axis"}},
       run_voxels},
      {"csg", "  issue 21's CSG curve: a cube minus 1..512 cylinders, time, records, mismatches against the ray\n"
              "  caster outside its edge band\n",
       {{"cylinders", "N,..", "1,2,4,8,16,32,64,128,256,512", "subtracted cylinders"}},
       run_csg},
  };
  return list;
}

std::string figure_help() {
  std::string s = CommandSpec{"figure fig2|fig8|fig10|table1|frontier|shadows|voxels|csg --out F.json[,F.csv] [OPTIONS]",
                              figure_common(false), ""}
                      .help();
  for (const Figure& f : figures()) {
    const std::string own = CommandSpec{"", f.own, ""}.help();
    s += f.name + ":\n" + f.what + own.substr(own.find('\n') + 1);
  }
  return s + "table1: --size defaults to 1024x1024 there (the paper's screen).\n";
}

// An option of another figure: "option --NAME does not apply to figure FIG".
void refuse_other_figures_options(const Args& all, const Figure& figure) {
  for (const Figure& other : figures())
    for (const OptionSpec& o : other.own)
      if (all.has(o.name) && std::none_of(figure.own.begin(), figure.own.end(),
                                          [&](const OptionSpec& m) { return m.name == o.name; }))
        throw UsageError("option --" + o.name + " does not apply to figure " + figure.name);
}

CommandSpec figure_spec(const Figure& f) { return CommandSpec{"figure " + f.name, figure_common(f.name == "table1") + f.own, ""}; }

}  // namespace

const std::vector<std::pair<std::string, CommandSpec>>& figure_specs() {
  static const std::vector<std::pair<std::string, CommandSpec>> specs = [] {
    std::vector<std::pair<std::string, CommandSpec>> out;
    for (const Figure& f : figures()) out.emplace_back("figure " + f.name, figure_spec(f));
    return out;
  }();
  return specs;
}


int run_figure(const std::vector<std::string>& argv) {
  if (print_help(argv, figure_help()) || argv.empty()) {
    if (argv.empty()) throw UsageError("name a figure: fig2, fig8, fig10, table1, frontier, shadows, voxels or csg");
    return 0;
  }
  const std::string name = argv[0];
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  static const CommandSpec every = [] {
    CommandSpec c{"", figure_common(false), ""};
    for (const Figure& f : figures()) c.options = c.options + f.own;
    return c;
  }();
  const Args all = Args::probe(rest, every);
  const auto figure = std::find_if(figures().begin(), figures().end(), [&](const Figure& f) { return f.name == name; });
  if (figure == figures().end())
    throw UsageError("unknown figure '" + name + "' (fig2, fig8, fig10, table1, frontier, shadows, voxels, csg)");
  refuse_other_figures_options(all, *figure);
  const CommandSpec& spec =
      std::find_if(figure_specs().begin(), figure_specs().end(), [&](const auto& f) { return f.first == "figure " + name; })
          ->second;
  const Args args(rest, spec);
  harness::FigureSettings s;
  s.path = parse_path(args);
  // The Vulkan path renders scenes (frontier); the other figures build on GL or the CPU.
  if (s.path == RenderPath::Vk && name != "frontier")
    throw UsageError("option --path vk: figure " + name + " runs on gl or cpu (vk renders figure frontier)");
  s.repeats = args.u32_in("repeats", 1, 1000);
  s.threads = args.u32_in("threads", 0, kMaxThreads);
  // figure shadows builds its light buffers on the CPU whatever the path.
  if (name != "table1" && name != "shadows")
    args.refuse_unless(s.path == RenderPath::Cpu, {"threads"},
                       "with --path " + std::string(to_string(s.path)) + " (the GPU inserts)");
  s.tau = usage_errors("tau", [&] { return parse_cull_threshold(args.str("tau")); });
  args.refuse_unless(args.has("picks"), {"targets", "memory-budgets"},
                     "without --picks (the targets and budgets choose the picks)");
  ProgressBar progress = ProgressBar::for_terminal("habuffer figure " + name, "runs", args.has("quiet"));
  s.on_progress = progress.callback();
  // Every file and value is checked before the first render.
  FigureRun run{args, s, {}, argv};
  harness::ResultTable table = figure->run(run);
  write_outputs(("figure " + name).c_str(), table, run.outputs.out, rest);
  return 0;
}

}  // namespace habuffer::cli
