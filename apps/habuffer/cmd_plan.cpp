// habuffer plan: from one counting pass, predict each technique's memory,
// max age, overflow, failure risk and PSNR, and recommend one (harness/plan.h).
#include <cstdio>

#include "commands.h"
#include "habuffer/option_rules.h"
#include "habuffer/progress.h"
#include "harness_cli.h"
#include "habuffer/harness/plan.h"

namespace habuffer::cli {
namespace {

constexpr const char* kHelp =
    "usage: habuffer plan (--scene NAME|FILE | --fragments F.csv) --out F.json[,F.csv] [--size WxH (256x256)]\n"
    "         [--target-psnr DB] [--loads L,.. (0.5,0.6,0.7,0.8,0.9,0.95)] [--trials N (3)] [--seed S] [--age-bits A]\n"
    "         [--quiet]\n"
    "  One counting pass (the exact capture) gives the fragment count and the depth complexity per pixel;\n"
    "  from them: memory of every technique and setting, the HA-buffer's max age and failure risk (SPEC 3's\n"
    "  insertion of a stream with the same per-pixel counts over N seeds), the layers' overflow and the\n"
    "  PSNR of the truncating ones. Recommends the cheapest lossless configuration, or the cheapest that\n"
    "  meets --target-psnr. A progress bar (loads simulated) shows on a terminal unless --quiet.\n";

}  // namespace

int run_plan(const std::vector<std::string>& argv) {
  if (print_help(argv, kHelp)) return 0;
  const Args args(argv, {"scene", "fragments", "size", "target-psnr", "loads", "trials", "seed", "age-bits", "out"}, {"quiet"});
  if (args.has("scene") == args.has("fragments")) throw UsageError("give exactly one of --scene and --fragments");
  harness::PlanSettings s;
  if (args.has("target-psnr")) s.target_psnr = args.real("target-psnr", 0.0);
  s.trials = args.u32("trials", 3, 1, 1000);
  s.seed = args.u64("seed", 1);
  s.age_bits = args.u32("age-bits", HABUFFER_DEFAULT_AGE_BITS, HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  s.loads.clear();
  for (const std::string& l : args.list("loads", "0.5,0.6,0.7,0.8,0.9,0.95"))
    s.loads.push_back(usage_errors("loads", [&] { return parse_load_factor(l); }));
  const std::vector<Extent> sizes = parse_sizes(args, "256x256");
  if (sizes.size() != 1) throw UsageError("--size takes one WxH");
  const harness::WorkloadSpec w =
      harness::parse_workload_spec(args.has("fragments") ? args.required("fragments") : args.required("scene"));
  const std::vector<std::string> outputs = parse_outputs(args, {w}).out;
  const auto context = context_for(w.fragments.empty(), "plan");
  const harness::Workload workload(w, sizes[0]);
  ProgressBar progress = ProgressBar::for_terminal("habuffer plan", "loads", args.has("quiet"));
  s.on_progress = progress.callback();
  harness::ResultTable table = harness::run_plan(workload, s);
  write_outputs("plan", table, outputs, argv);
  std::printf("habuffer plan: recommended %s (%s fragments, depth complexity up to %s)\n",
              table.notes["recommendation"].c_str(), table.notes["fragments"].c_str(),
              table.notes["max_depth_complexity"].c_str());
  return 0;
}

}  // namespace habuffer::cli
