// habuffer plan: from one counting pass, predict each technique's memory,
// max age, overflow, failure risk and PSNR, and recommend one (harness/plan.h).
#include <cstdio>

#include "commands.h"
#include "file_values.h"
#include "habuffer/option_rules.h"
#include "habuffer/progress.h"
#include "harness_cli.h"
#include "technique_flags.h"
#include "habuffer/harness/plan.h"

namespace habuffer::cli {
const CommandSpec& plan_spec() {
  static const CommandSpec spec{
      "plan (--scene NAME|FILE | --fragments F.csv) --out F.json[,F.csv] [OPTIONS]",
      std::vector<OptionSpec>{
          {"scene", "NAME|FILE", "", "the scene, with options", reads_in(scene_word_file, "{}")},
          {"fragments", "F.csv", "", "a fragment file instead", reads()},
          {"target-psnr", "DB", "", "recommend the cheapest configuration that meets it (default: lossless)"},
          {"memory-budget", "B", "",
           "bytes per fragment: recommend only within it (the most accurate there when none meets the aim)"},
          {"loads", "L1,L2,...", "0.5,0.6,0.7,0.8,0.9,0.95", "the loads in (0, 1] predicted (as sweep's)"},
          {"trials", "N", "3",
           "seeds of the HA-buffer's simulated insertion (a prediction: fewer than stats' 5 trials)"},
          {"seed", "S", "1", "the first of them"},
          technique_option_spec("age-bits")} +
          harness_options({"out", "size", "quiet"}),
      "  One counting pass (the exact capture) gives the fragment count and the depth complexity per pixel;\n"
      "  from them: memory of every technique and setting, the HA-buffer's max age and failure risk (SPEC 3's\n"
      "  insertion of a stream with the same per-pixel counts over N seeds), the layers' overflow and the\n"
      "  PSNR of the truncating ones. Recommends the cheapest lossless configuration, or the cheapest that\n"
      "  meets --target-psnr, within --memory-budget when given. A progress bar (loads simulated) shows on\n"
      "  a terminal unless --quiet.\n"};
  return spec;
}

int run_plan(const std::vector<std::string>& argv) {
  if (print_help(argv, plan_spec())) return 0;
  const Args args(argv, plan_spec());
  if (args.has("scene") == args.has("fragments")) throw UsageError("give exactly one of --scene and --fragments");
  harness::PlanSettings s;
  if (args.has("target-psnr")) {
    s.target_psnr = args.real("target-psnr", 0.0);  // finite (parse_float64)
    if (!(*s.target_psnr > 0.0))
      throw UsageError("option --target-psnr: " + args.str("target-psnr") + " is not a PSNR above 0 dB");
  }
  if (args.has("memory-budget")) {
    s.memory_budget = args.real("memory-budget", 0.0);  // finite (parse_float64)
    if (!(*s.memory_budget >= 0.0))
      throw UsageError("option --memory-budget: " + args.str("memory-budget") + " is not a number of bytes per fragment at least 0");
  }
  s.trials = args.u32_in("trials", 1, 1000);
  s.seed = args.u64_in("seed");
  s.age_bits = args.u32_in("age-bits", HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  s.loads.clear();
  for (const std::string& l : args.list("loads"))
    s.loads.push_back(usage_errors("loads", [&] { return parse_load_factor(l); }));
  const std::vector<Extent> sizes = parse_sizes(args);
  if (sizes.size() != 1) throw UsageError("--size takes one WxH");
  const harness::WorkloadSpec w = args.has("fragments") ? harness::fragment_workload(args.required("fragments"))
                                                         : harness::parse_workload_spec(args.required("scene"));
  const std::vector<std::string> outputs = parse_outputs(args).out;
  const auto context = context_for(w.fragments.empty(), "plan");
  const harness::Workload workload(w, sizes[0]);
  ProgressBar progress = ProgressBar::for_terminal("habuffer plan", "loads", args.has("quiet"));
  s.on_progress = progress.callback();
  harness::ResultTable table = harness::run_plan(workload, s);
  write_outputs("plan", table, outputs, argv);
  std::printf("habuffer plan: recommended %s (%s fragments, depth complexity up to %s)\n",
              table.notes["recommendation"].c_str(), table.notes["fragments"].c_str(),
              table.notes["max_depth_complexity"].c_str());
  if (s.memory_budget) std::printf("habuffer plan: budget %s\n", table.notes["budget"].c_str());
  return 0;
}

}  // namespace habuffer::cli
