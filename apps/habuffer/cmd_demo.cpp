// habuffer demo: the CPU path end to end on a generated stream, with a check
// that parallel insertion reproduces the serial table bit for bit.
#include <chrono>
#include <cstdio>
#include <optional>
#include <span>

#include "commands.h"
#include "file_values.h"
#include "gl_build.h"
#include "habuffer/fragment_streams.h"
#include "habuffer/interchange.h"
#include "hash_options.h"
#include "loss_report.h"
#include "report_json.h"

namespace habuffer::cli {
namespace {

double timed_ms(auto&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

bool same_tables(const HaBuffer& a, const HaBuffer& b) {
  if (a.table() != b.table() || a.max_age().ages() != b.max_age().ages()) return false;
  for (std::uint64_t s = 0; s < a.slot_count(); ++s)
    if (a.slot(s) != b.slot(s)) return false;
  return true;
}

}  // namespace

const CommandSpec& demo_spec() {
  static const CommandSpec spec{
      "demo [OPTIONS]",
      std::vector<OptionSpec>{
          {"screen", "WxH", "1024x1024", "the screen (a full frame's, as render's --size)"},
          {"stream", "coherent|random", "coherent", "the generated stream's shape"},
          {"fragments", "N", "", "the stream's fragments (default: the screen's area)"},
          {"load", "L", "0.5", "sizes the table for this load of the fragments, in (0, 1] (unless --table)"},
          {"table", "WxH", "", "the table (default: from --load)"},
          {"path", "cpu|gl", "cpu",
           "the second build: parallel on the CPU (the default: demo checks SPEC 9 on the CPU path), or on the GPU"},
          {"stats", "STATS.json", "", "the builds' counters, sizes and times", writes()},
          {"lists", "LISTS.csv", "", "the per-pixel sorted lists", writes()}} +
          shared_options({"layout", "age-bits", "offsets", "seed", "block", "early-cull", "iter-limit", "lossless",
                          "max-attempts", "threads", "insert-mode", "insert-order"}),
      "  --seed seeds the stream and the offsets. Builds the table serially on the CPU, then in parallel\n"
      "  (--path cpu) or on the GPU (--path gl), and checks that both tables are bit-identical (SPEC 9).\n"};
  return spec;
}

namespace {

// The command line with demo's defaults added: the screen, and the table of
// --load for --fragments; the stream's size in `count`.
std::vector<std::string> with_demo_defaults(const std::vector<std::string>& argv, std::uint64_t& count) {
  std::vector<std::string> with_defaults = argv;
  const Args probe = Args::probe(argv, demo_spec());
  const Extent screen = probe.size("screen");
  count = probe.u64("fragments", screen.area(), 1, std::uint64_t{1} << 32);
  const double load = probe.real("load");
  if (!(load > 0.0 && load <= 1.0)) throw UsageError("option --load: must be in (0, 1]");
  if (!probe.has("screen")) with_defaults.insert(with_defaults.end(), {"--screen", screen.str()});
  if (!probe.has("table"))
    with_defaults.insert(with_defaults.end(),
                         {"--table", usage_errors("load", [&] { return table_for_load(screen, count, load).str(); })});
  return with_defaults;
}

// The two builds of the demo: one thread, then the chosen path.
struct DemoBuilds {
  std::optional<BuildResult> one, many;  ///< serial; parallel or GPU
  double ms_one = 0.0;                   ///< the serial insertion's time
  BuildTiming timing;                    ///< the second build's
};

DemoBuilds build_demo_tables(const HashOptions& options, std::span<const Fragment> fragments) {
  InsertOptions serial = options.insert;
  serial.threads = 1;
  serial.mode = InsertMode::Auto;
  DemoBuilds b;
  b.timing.threads = options.gl ? 1 : resolve_threads(options.insert.threads);
  // Tables are allocated before the clock starts: the times are insertion only.
  const OffsetSequence offsets = options.offsets.make(options.config.table, options.config.record_layout().max_age());
  b.one.emplace(BuildResult{HaBuffer(options.config, offsets), {}, {}, std::nullopt});
  b.ms_one = timed_ms([&] { b.one->counters = b.one->buffer.insert(fragments, serial); });
  if (options.gl) {
    b.many.emplace(build_ha_on_gl(options, fragments, b.timing));
    return b;
  }
  b.many.emplace(BuildResult{HaBuffer(options.config, offsets), {}, {}, std::nullopt});
  b.timing.build_ms = timed_ms([&] { b.many->counters = b.many->buffer.insert(fragments, options.insert); });
  b.timing.insert_order = to_string(b.many->buffer.last_insert_order());
  b.many->attempts.push_back({options.config.table, b.many->counters, options.config.table.area()});
  return b;
}

void print_demo(const HashOptions& options, const StreamOptions& so, std::size_t fragments, const DemoBuilds& b,
                const BuildReport& report, bool identical) {
  std::printf("habuffer demo: %s stream, %llu fragments on screen %s, table %s (%s, %u age bits, %s offsets)\n",
              to_string(so.kind).c_str(), static_cast<unsigned long long>(fragments),
              options.config.screen.str().c_str(), b.many->buffer.table().str().c_str(),
              to_string(options.config.layout).c_str(), options.config.age_bits, options.offsets_name.c_str());
  std::printf("  stored %llu (duplicates %llu, culled %llu, invalid %llu, failed %llu), load %.3f, "
              "max age %u, mean age %.3f, memory %.1f MiB\n",
              static_cast<unsigned long long>(report.stored),
              static_cast<unsigned long long>(report.counters.duplicates),
              static_cast<unsigned long long>(report.counters.culled),
              static_cast<unsigned long long>(report.counters.invalid),
              static_cast<unsigned long long>(report.counters.failures()), report.load_factor, report.max_age,
              report.mean_age, static_cast<double>(report.memory_bytes) / (1 << 20));
  const std::string second = options.gl ? "gl " + b.timing.gl_atomic_mode + " on " + b.timing.gl_renderer
                                        : std::to_string(b.timing.threads) + " threads";
  const double ms_many = b.timing.build_ms;
  std::printf("  insert: 1 thread %.1f ms (%.1f M fragments/s), %s %.1f ms (%.1f M fragments/s); tables %s\n",
              b.ms_one, static_cast<double>(fragments) / b.ms_one * 1e-3, second.c_str(), ms_many,
              static_cast<double>(fragments) / ms_many * 1e-3,
              identical ? "bit-identical" : "DIFFER (bug: SPEC 9 determinism)");
}

}  // namespace

int run_demo(const std::vector<std::string>& argv) {
  if (print_help(argv, demo_spec())) return 0;
  std::uint64_t count = 0;
  const Args args(with_demo_defaults(argv, count), demo_spec());
  args.used_by_probe({"fragments", "load"});
  HashOptions options = parse_hash_options(args);

  StreamOptions so;
  so.kind = parse_stream_kind(args.str("stream"));
  so.count = count;
  so.seed = args.u64_in("seed");
  const std::vector<Fragment> fragments = make_stream(options.config.screen, so);

  if (options.lossless) throw UsageError("demo does not take --lossless (use build-lists)");
  const DemoBuilds b = build_demo_tables(options, fragments);
  const BuildReport report = summarize(b.many->buffer, b.many->counters);
  const bool identical = options.config.early_cull_tau > 0.0f || same_tables(b.one->buffer, b.many->buffer);
  print_demo(options, so, fragments.size(), b, report, identical);
  warn_losses("habuffer demo", report.counters, "", "a larger --table (or lower --load) or more --age-bits keeps them");
  if (args.has("lists")) write_lists(args.required("lists"), b.many->buffer);
  if (args.has("stats")) {
    JsonWriter json;
    json.begin_object().field("stream", to_string(so.kind));
    write_build_stats(json, options, b.many->buffer, b.many->attempts, report, b.timing);
    json.field("serial_build_ms", b.ms_one).field("parallel_identical", identical).end_object();
    json.save(args.required("stats"));
  }
  return identical && report.stored == report.counters.stored() ? 0 : 1;
}

}  // namespace habuffer::cli
