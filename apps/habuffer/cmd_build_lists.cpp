// habuffer build-lists: fragment CSV in, per-pixel sorted lists out.
#include <chrono>
#include <cstdio>

#include "commands.h"
#include "gl_build.h"
#include "habuffer/file_roles.h"
#include "habuffer/interchange.h"
#include "hash_options.h"
#include "loss_report.h"
#include "report_json.h"

namespace habuffer::cli {
namespace {

constexpr const char* kHelp =
    "usage: habuffer build-lists --in FRAGS.csv --out LISTS.csv --screen WxH [--table WxH] [--layout 64|32]\n"
    "         [--age-bits N] [--offsets random|farthest|OFFSETS.csv] [--seed N] [--block B] [--threads N]\n"
    "         [--early-cull TAU] [--lossless [--max-attempts N]] [--iter-limit N] [--stats STATS.json]\n"
    "         [--insert-mode auto|serial|atomic|owner] [--path cpu|gl]\n"
    "         [--dump-table TABLE.csv] [--dump-max-age MAXAGE.csv]\n"
    "  --threads 0 uses every hardware thread; every insert mode builds the same table. Exit codes: 0 ok, 1 bad data or lossless failure, 2 bad usage.\n";

}  // namespace

int run_build_lists(const std::vector<std::string>& argv) {
  if (print_help(argv, kHelp)) return 0;
  auto valued = hash_valued_options();
  valued.insert({"in", "out", "stats", "dump-table", "dump-max-age"});
  const Args args(argv, valued, hash_flag_options());
  const std::string in = args.required("in");
  const std::string out = args.required("out");
  const HashOptions options = parse_hash_options(args);
  FileRoles files;
  files.input("--in", in).output("--out", out);
  add_offsets_input(files, options);
  for (const char* o : {"stats", "dump-table", "dump-max-age"})
    if (args.has(o)) files.output(std::string("--") + o, args.required(o));
  check_files(files);

  const std::vector<Fragment> fragments = read_fragments(in, options.config.screen);
  BuildTiming timing{0.0, resolved_threads(options.insert.threads), {}, {}};
  std::optional<BuildResult> built;
  if (options.gl) {
    built.emplace(build_on_gl(options, fragments, timing));
  } else {
    const auto t0 = std::chrono::steady_clock::now();
    built.emplace(build(options.config, options.offsets, fragments, options.insert, options.policy, options.max_attempts));
    timing.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  }
  BuildResult& result = *built;

  write_lists(out, result.buffer);
  if (args.has("dump-table")) write_table(args.required("dump-table"), result.buffer);
  if (args.has("dump-max-age")) write_max_age(args.required("dump-max-age"), result.buffer);
  const BuildReport report = summarize(result.buffer, result.counters);
  if (args.has("stats")) {
    JsonWriter json;
    json.begin_object();
    json.field("in", in);
    write_build_stats(json, options, result, report, timing);
    json.end_object();
    json.save(args.required("stats"));
  }
  if (report.stored != report.counters.stored())
    throw std::logic_error("accounting broken: table holds " + std::to_string(report.stored) +
                           " records, counters say " + std::to_string(report.counters.stored()));
  if (options.lossless && !result.lossless()) {
    report_lossless_failure("build-lists", result.counters,
                            " after " + std::to_string(result.attempts.size()) + " attempts (last table " +
                                result.buffer.table().str() + ", AMAX " +
                                std::to_string(options.config.record_layout().max_age()) +
                                "); a pixel with more than AMAX distinct fragments needs more --age-bits");
    return 1;
  }
  warn_losses("build-lists", result.counters, "", kLosslessHint);
  return 0;
}

}  // namespace habuffer::cli
