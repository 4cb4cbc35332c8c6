// habuffer sweep: throughput, probes and ages of one fixed view against the
// load factor (harness/sweep.h).
#include <cstdio>

#include "commands.h"
#include "file_values.h"
#include "harness_cli.h"
#include "habuffer/harness/sweep.h"
#include "habuffer/progress.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::cli {
const CommandSpec& sweep_spec() {
  static const CommandSpec spec{
      "sweep (--scene NAME|FILE | --fragments F.csv) --out F.json[,F.csv] [OPTIONS]",
      std::vector<OptionSpec>{
          {"scene", "NAME|FILE", "", "the scene, with options (planes:order=front:count=32, hairball:opacity=0.25)", reads_in(scene_word_file, "{}")},
          {"fragments", "F.csv", "", "a fragment file instead (CPU path)", reads()},
          {"technique", "T", "ha", "one technique word, NAME[:cull=TAU][:sat][:age=A][:occ][:words=D] (habuffer "
                                   "bench --help): the load sets its size"},
          {"loads", "L1,L2,...", "0.5,0.6,0.7,0.8,0.9,0.95", "the loads the technique is sized for"},
          {"offsets", "random|farthest", "random", "the HA-buffer's offsets (no file: each run draws its own)"}} +
          harness_options({"out", "size", "repeats", "path", "seed", "threads", "insert-order", "quiet"}),
      "  One fixed view (the scene's default camera); the technique sized for each load of the scene's\n"
      "  fragments (the HA-buffer's table, the lists' pool, the arrays' or k-buffer's layers); N runs per\n"
      "  load with offsets seeded S + run, interleaved load by load. One row per load: load, throughput to\n"
      "  sorted lists (sorted_mfrag_per_s median, min, max: the gather plus a separate sort pass, sort_ms),\n"
      "  the gather's alone (mfrag_per_s), slot writes (GL) and probes per fragment, mean_age (95% CI),\n"
      "  p99_age, max_age, the age histogram, every counter, memory_bytes.\n"};
  return spec;
}

int run_sweep(const std::vector<std::string>& argv) {
  if (print_help(argv, sweep_spec())) return 0;
  const Args args(argv, sweep_spec());
  if (args.has("scene") == args.has("fragments")) throw UsageError("give exactly one of --scene and --fragments");
  harness::SweepSettings s;
  s.path = args.has("fragments") ? RenderPath::Cpu : parse_path(args);
  if (args.has("fragments") && args.has("path") && args.str("path", "") != "cpu")
    throw UsageError("--fragments renders on the CPU path: drop --path " + args.str("path", ""));
  const std::vector<harness::TechniqueSpec> t = parse_techniques(args, "technique");
  if (t.size() != 1) throw UsageError("--technique takes one technique (bench compares several)");
  s.technique = t[0];
  s.loads = parse_reals(args, "loads");
  s.repeats = args.u32_in("repeats", 1, 1000);
  s.seed = args.u64_in("seed");
  args.refuse_unless(descriptor(s.technique.technique).takes("offsets"), {"offsets", "seed"},
                     "with --technique " + to_string(s.technique.technique) + " (offsets apply to " +
                         techniques_taking("offsets") + ")");
  const std::optional<OffsetGenerator> offsets = parse_offset_generator(args.str("offsets"));
  if (!offsets) throw UsageError("--offsets must be random or farthest");
  s.offsets = *offsets;
  s.threads = args.u32_in("threads", 0, kMaxThreads);
  s.insert_order = insert_order_option(args);
  args.refuse_unless(s.path == RenderPath::Cpu, {"threads", "insert-order"},
                     "with --path " + std::string(to_string(s.path)) + " (the GPU inserts)");
  const std::vector<Extent> sizes = parse_sizes(args);
  if (sizes.size() != 1) throw UsageError("--size takes one WxH (bench compares several)");
  try {
    harness::validate_sweep(s);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  const harness::WorkloadSpec w =
      harness::parse_workload_spec(args.has("fragments") ? args.required("fragments") : args.required("scene"));
  const std::vector<std::string> outputs = parse_outputs(args).out;
  const auto context = context_for(w.fragments.empty(), "sweep");
  const harness::Workload workload(w, sizes[0]);
  ProgressBar progress = ProgressBar::for_terminal("habuffer sweep", "runs", args.has("quiet"));
  s.on_progress = progress.callback();
  harness::ResultTable table = harness::run_sweep(workload, s);
  write_outputs("sweep", table, outputs, argv);
  return 0;
}

}  // namespace habuffer::cli
