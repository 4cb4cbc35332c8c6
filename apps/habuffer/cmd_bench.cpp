// habuffer bench: techniques x scenes x sizes, interleaved, with the floors
// and the error against the exact reference (harness/bench.h).
#include <cstdio>

#include "commands.h"
#include "file_values.h"
#include "harness_cli.h"
#include "habuffer/harness/bench.h"
#include "habuffer/progress.h"

namespace habuffer::cli {
const CommandSpec& bench_spec() {
  static const CommandSpec spec{
      "bench --scenes S1,S2,... --techniques T1,T2,... --out F.json[,F.csv] [OPTIONS]",
      std::vector<OptionSpec>{
          {"scenes", "S1,S2,...", "", "the scenes (required; S below)", reads_in(scene_word_files, "{}")},
          {"techniques", "T1,T2,...", "", "the techniques and their knobs (required; T below)"},
          {"no-floors", "", "", "skip the floors"},
          {"model", "gpu", "", "add the GPU traffic model's columns (model_*) beside the timings"}} +
          harness_options({"out", "size", "path", "repeats", "seed", "threads", "insert-order", "quiet"}),
      "  Every technique on every scene at every size, repetitions interleaved (each combination once per\n"
      "  round) with the floors (one atomic add per fragment; unsorted blending; on the CPU path the exact\n"
      "  floor: bucket by pixel, sort, composite from the buckets) measured in every round.\n"
      "  One row per combination: gather_ms, resolve_ms, total_ms (medians, min and max), memory_bytes,\n"
      "  bytes_per_fragment, every counter, psnr, rmse and max_error against the exact reference, the\n"
      "  floors and the ratios to them. --model gpu adds, for ha, lists, sorted-lists, arrays and kbuffer, the\n"
      "  frame's GPU traffic (sectors, lines, atomics, conflicts, dependent-load chains per pass) and an H100 time.\n"
      "  S: a scene name or mesh file with options (planes:order=front:count=32), or a fragment CSV (CPU).\n"
      "  T: NAME[:KNOB...], NAME a technique (habuffer techniques lists them); knobs\n" +
      technique_knob_help() + "     e.g. kbuffer:k=8:occ.\n"};
  return spec;
}

int run_bench(const std::vector<std::string>& argv) {
  if (print_help(argv, bench_spec())) return 0;
  const Args args(argv, bench_spec());
  harness::BenchSettings s;
  s.path = parse_path(args);
  s.scenes = parse_scenes(args, "scenes");
  s.techniques = parse_techniques(args, "techniques");
  s.sizes = parse_sizes(args);
  s.repeats = args.u32_in("repeats", 1, 1000);
  s.seed = args.u64_in("seed");
  s.threads = args.u32_in("threads", 0, kMaxThreads);
  s.insert_order = insert_order_option(args);
  args.refuse_unless(s.path == RenderPath::Cpu, {"threads", "insert-order"},
                     "with --path " + std::string(to_string(s.path)) + " (the GPU inserts)");
  s.floors = !args.has("no-floors");
  if (args.has("model")) {
    if (args.str("model") != "gpu") throw UsageError("--model must be gpu, not '" + args.str("model") + "'");
    s.model_gpu = true;
  }
  try {
    harness::validate_bench(s);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  bool needs_gl = false;
  for (const harness::WorkloadSpec& w : s.scenes) needs_gl |= w.fragments.empty();
  const std::vector<std::string> outputs = parse_outputs(args).out;
  const auto context = context_for(needs_gl, "bench");
  ProgressBar progress = ProgressBar::for_terminal("habuffer bench", "runs", args.has("quiet"));
  s.on_progress = progress.callback();
  harness::ResultTable table = harness::run_bench(s);
  write_outputs("bench", table, outputs, argv);
  return 0;
}

}  // namespace habuffer::cli
