// habuffer build-lists: fragment CSV in, per-pixel sorted lists out.
#include <chrono>
#include <cstdio>

#include "commands.h"
#include "file_values.h"
#include "gl_build.h"
#ifdef HABUFFER_WITH_VK
#include "vk_build.h"
#endif
#include "habuffer/techniques/ha/ha_buffer.h"
#include "habuffer/file_roles.h"
#include "habuffer/interchange.h"
#include "hash_options.h"
#include "technique_flags.h"
#include "vulkan_path.h"
#include "loss_report.h"
#include "report_json.h"

namespace habuffer::cli {
namespace {
constexpr const char* kBuildPaths = kHasVulkanPath ? "cpu|gl|vk" : "cpu|gl";
}  // namespace

const CommandSpec& build_lists_spec() {
  static const CommandSpec spec{
      "build-lists --in FRAGS.csv --out LISTS.csv --screen WxH [OPTIONS]",
      std::vector<OptionSpec>{
          {"in", "FRAGS.csv", "", "the fragments (required)", reads()},
          {"out", "LISTS.csv", "", "the per-pixel sorted lists (required)", writes()},
          {"screen", "WxH", "", "the screen (required)"},
          {"stats", "STATS.json", "", "the build's counters, sizes and times", writes()},
          {"dump-table", "TABLE.csv", "", "the HA-buffer's table, slot by slot", writes()},
          {"dump-max-age", "MAXAGE.csv", "", "the HA-buffer's max-age table", writes()},
          {"path", kBuildPaths, "cpu",
           "where the lists are built: cpu here (a fragment file's reference build), gl (OpenGL 4.5) or vk (Vulkan, "
           "where built; ha and lists so far) through the GPU's compute entry"},
          {"table", "WxH", "",
           "the HA-buffer's table (default: the screen; render's auto sizes it from a counting pass)"}} +
          shared_options({"technique"}) + technique_option_specs(false) + technique_option_specs(true) +
          shared_options(
              {"layout", "offsets", "seed", "lossless", "max-attempts", "threads", "insert-mode", "insert-order"}),
      "  Exit codes: 0 ok, 1 bad data or lossless failure, 2 bad usage.\n"
      "  Every technique that stores lists writes the same lists CSV; identical records are merged as duplicates,\n"
      "  so an exact technique's lists equal the HA-buffer's byte for byte.\n"};
  return spec;
}

namespace {

// Refuses a technique without lists, before any work.
void check_build_request(const HashOptions& options) {
  if (!stores_lists(options.technique.technique))
    throw UsageError("--technique " + to_string(options.technique.technique) +
                     " stores no lists (it blends every fragment into the image): use habuffer render");
}

// The build on the chosen path, timed.
TechniqueBuild build_lists(const HashOptions& options, const TechniqueConfig& config,
                           std::span<const Fragment> fragments, BuildTiming& timing) {
  timing.threads = resolve_threads(options.insert.threads);
  if (options.gl) return build_on_gl(options, fragments, timing);
#ifdef HABUFFER_WITH_VK
  if (options.vk) return build_on_vk(options, fragments, timing);
#endif
  const auto t0 = std::chrono::steady_clock::now();
  TechniqueBuild built =
      build_technique(config, options.offsets, fragments, options.insert, options.policy, options.max_attempts);
  timing.build_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  timing.insert_order = to_string(built.buffer->last_insert_order());
  return built;
}

// The lists, the hash table's dumps and the stats; the report, checked against the counters.
BuildReport write_build_outputs(const Args& args, const std::string& in, const std::string& out,
                                const HashOptions& options, const TechniqueBuild& result, const BuildTiming& timing) {
  write_lists(out, *result.buffer);
  if (const HaBuffer* ha = as_hash_table(*result.buffer)) {
    if (args.has("dump-table")) write_table(args.required("dump-table"), *ha);
    if (args.has("dump-max-age")) write_max_age(args.required("dump-max-age"), *ha);
  }
  const BuildReport report = summarize(*result.buffer, result.counters);
  if (args.has("stats")) {
    JsonWriter json;
    json.begin_object();
    json.field("in", in);
    write_build_stats(json, options, *result.buffer, result.attempts, report, timing);
    json.end_object();
    json.save(args.required("stats"));
  }
  if (report.stored != report.counters.stored())
    throw std::logic_error("accounting broken: the " + to_string(result.buffer->technique()) + " buffer holds " +
                           std::to_string(report.stored) +
                           " records, counters say " + std::to_string(report.counters.stored()));
  return report;
}

// The loss warning or the lossless failure (exit 1) of a finished build: the
// library's reason (lossless_failure_reason, the Python module's DataError's).
int report_build_losses(const HashOptions& options, const TechniqueConfig& config, std::span<const Fragment> fragments,
                        const TechniqueBuild& result) {
  if (options.lossless && !result.lossless()) {
    report_lossless_failure("habuffer build-lists", result.counters,
                            lossless_failure_reason(result, fragments, options.max_attempts));
    return 1;
  }
  std::optional<PixelDepth> too_deep = result.too_deep;
  // One attempt and age failures: no loop looked, look now for the warning.
  if (!too_deep && result.counters.failed_age > 0) too_deep = pixel_beyond_every_table(config, fragments);
  if (too_deep) {
    warn_losses("habuffer build-lists", result.counters, "", too_deep_message(*too_deep, options.config.age_bits));
    return 0;
  }
  warn_losses("habuffer build-lists", result.counters, "", lossless_hint(options.technique.technique));
  return 0;
}

}  // namespace

int run_build_lists(const std::vector<std::string>& argv) {
  if (print_help(argv, build_lists_spec().help() + technique_help())) return 0;
  const Args args(argv, build_lists_spec());
  const std::string in = args.required("in");
  const std::string out = args.required("out");
  HashOptions options = parse_hash_options(args, true);
  check_build_request(options);

  const std::vector<Fragment> fragments = read_fragments(in, options.config.screen);
  // Both paths grow by the library's one rule (lossless_attempts): no attempt
  // grows for a pixel deeper than AMAX, which no table holds.
  const TechniqueConfig config = technique_config(options);
  BuildTiming timing;
  const TechniqueBuild result = build_lists(options, config, fragments, timing);
  write_build_outputs(args, in, out, options, result, timing);
  return report_build_losses(options, config, fragments, result);
}

}  // namespace habuffer::cli
