// habuffer sweep: throughput, probes and ages of one fixed view against the
// load factor (harness/sweep.h).
#include <cstdio>

#include "commands.h"
#include "harness_cli.h"
#include "habuffer/harness/sweep.h"
#include "habuffer/progress.h"
#include "habuffer/technique_descriptor.h"

namespace habuffer::cli {
namespace {

constexpr const char* kHelp =
    "usage: habuffer sweep (--scene NAME|FILE | --fragments F.csv) --out F.json[,F.csv] [--size WxH (256x256)]\n"
    "         [--loads L1,L2,... (0.5,0.6,0.7,0.8,0.9,0.95)] [--repeats N (3)] [--path gl|cpu] [--technique T (ha)]\n"
    "         [--seed S (1)] [--offsets random|farthest] [--threads N]\n"
    "         [--insert-order auto|arrival|pixel] [--quiet]\n"
    "  One fixed view (the scene's default camera); the technique sized for each load of the scene's\n"
    "  fragments (the HA-buffer's table, the lists' pool, the arrays' or k-buffer's layers); N runs per\n"
    "  load with offsets seeded S + run, interleaved load by load. One row per load: load, gather\n"
    "  throughput (mfrag_per_s median, min, max), slot writes (GL) and probes per fragment, mean_age\n"
    "  (95% CI), p99_age, max_age, the age histogram, every counter, memory_bytes.\n"
    "  SCENE may carry options: planes:order=front:count=32, quads:spread=0.5, hairball:opacity=0.25.\n"
    "  T: NAME[:cull=TAU][:sat][:age=A][:occ][:words=D], e.g. ha:cull=0.99 (see 'habuffer bench --help').\n";

}  // namespace

int run_sweep(const std::vector<std::string>& argv) {
  if (print_help(argv, kHelp)) return 0;
  const Args args(argv, {"scene", "fragments", "size", "loads", "repeats", "path", "technique", "seed", "offsets",
                         "threads", "insert-order", "out"},
                  {"quiet"});
  if (args.has("scene") == args.has("fragments")) throw UsageError("give exactly one of --scene and --fragments");
  harness::SweepSettings s;
  s.path = args.has("fragments") ? RenderPath::Cpu : parse_path(args);
  if (args.has("fragments") && args.has("path") && args.str("path", "") == "gl")
    throw UsageError("--fragments renders on the CPU path: drop --path gl");
  const std::vector<harness::TechniqueSpec> t = parse_techniques(args, "technique", "ha");
  if (t.size() != 1) throw UsageError("--technique takes one technique (bench compares several)");
  s.technique = t[0];
  s.loads = parse_reals(args, "loads", "0.5,0.6,0.7,0.8,0.9,0.95");
  s.repeats = args.u32("repeats", 3, 1, 1000);
  s.seed = args.u64("seed", 1);
  args.refuse_unless(descriptor(s.technique.technique).takes("offsets"), {"offsets", "seed"},
                     "with --technique " + to_string(s.technique.technique) + " (offsets apply to " +
                         techniques_taking("offsets") + ")");
  const std::string offsets = args.str("offsets", "random");
  if (offsets != "random" && offsets != "farthest") throw UsageError("--offsets must be random or farthest");
  s.offsets = offsets == "random" ? OffsetGenerator::Random : OffsetGenerator::Farthest;
  s.threads = args.u32("threads", 0, 0, kMaxThreads);
  s.insert_order = insert_order_option(args);
  args.refuse_unless(s.path == RenderPath::Cpu, {"threads", "insert-order"}, "with --path gl (the GPU inserts)");
  const std::vector<Extent> sizes = parse_sizes(args, "256x256");
  if (sizes.size() != 1) throw UsageError("--size takes one WxH (bench compares several)");
  try {
    harness::validate_sweep(s);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  const harness::WorkloadSpec w =
      harness::parse_workload_spec(args.has("fragments") ? args.required("fragments") : args.required("scene"));
  const std::vector<std::string> outputs = parse_outputs(args, {w}).out;
  const auto context = context_for(w.fragments.empty(), "sweep");
  const harness::Workload workload(w, sizes[0]);
  ProgressBar progress = ProgressBar::for_terminal("habuffer sweep", "runs", args.has("quiet"));
  s.on_progress = progress.callback();
  harness::ResultTable table = harness::run_sweep(workload, s);
  write_outputs("sweep", table, outputs, argv);
  return 0;
}

}  // namespace habuffer::cli
