// habuffer stats: experiments on age vs load over the CPU-path model.
#include <cmath>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <charconv>

#include "cli_args.h"
#include "habuffer/memory_budget.h"
#include "commands.h"
#include "file_values.h"
#include "technique_flags.h"
#include "habuffer/age_experiment.h"
#include "habuffer/experiment_columns.h"
#include "habuffer/key_experiment.h"
#include "key_options.h"
#include "habuffer/csv.h"
#include "habuffer/file_roles.h"
#include "habuffer/json_writer.h"
#include "habuffer/printable.h"
#include "habuffer/progress.h"

namespace habuffer::cli {
namespace {

// The rows as CSV, the columns' own list and formats (experiment_columns.h).
template <class Row>
void write_rows_csv(const std::string& path, const std::vector<Row>& rows,
                    std::span<const RowColumn<Row>> columns) {
  CsvWriter out(path);
  std::string line;
  for (const RowColumn<Row>& col : columns)
    if (col.csv_format) {
      if (!line.empty()) line += ',';
      line.append(col.name);
    }
  out.text(line + "\n");
  for (const Row& r : rows) {
    line.clear();
    bool first = true;
    for (const RowColumn<Row>& col : columns) {
      if (!col.csv_format) continue;
      if (!first) line += ',';
      first = false;
      line += csv_cell(col.get(r), col.csv_format);
    }
    out.text(line + "\n");
  }
  out.close();
}

// The rows as a JSON array "rows" of objects, one key per column.
template <class Row>
void write_rows_json(JsonWriter& j, const std::vector<Row>& rows, std::span<const RowColumn<Row>> columns) {
  j.key("rows").begin_array();
  for (const Row& r : rows) {
    j.begin_object();
    for (const RowColumn<Row>& col : columns)
      std::visit([&](const auto& v) { j.field(col.name, v); }, col.get(r));
    j.end_object();
  }
  j.end_array();
}

void write_json(const std::string& path, const ExperimentConfig& c, const std::vector<ExperimentRow>& rows) {
  JsonWriter j;
  j.begin_object().key("screen").begin_array().value(c.screen.x).value(c.screen.y).end_array();
  const Extent table = c.table == Extent{} ? c.screen : c.table;
  j.key("table").begin_array().value(table.x).value(table.y).end_array();
  j.field("stream", to_string(c.stream.kind)).field("trials", c.trials).field("seed", c.seed);
  j.field("age_bits", c.age_bits).field("block", c.block);
  write_rows_json(j, rows, experiment_columns());
  j.end_object();
  j.save(path);
}

}  // namespace

const CommandSpec& stats_spec() {
  static const CommandSpec spec{
      "stats [OPTIONS]",
      {{"screen", "WxH", "128x128", "the screen (small: every trial builds a table)"},
       {"table", "WxH", "", "the table (default: the screen)"},
       {"loads", "L1,L2,...", "0.5,0.8,0.9",
        "loads in (0, 4]: fragments per trial = load x table slots (three: each runs every variant and trial; "
        "sweep and plan take six)"},
       {"trials", "N", "5", "trials per load and variant"},
       {"seed", "S", "1", "the streams' seed"},
       {"stream", "random|coherent|stacked|hot", "random", "the streams' shape"},
       {"spread", "S", "1", "stacked streams: their spread in [0, 1]"},
       {"probing", "coherent,independent|all", "coherent,independent", "probing variants"},
       {"policy", "robinhood,fcfs|all", "robinhood", "insertion policies"},
       {"offsets", "random,farthest|all", "random",
        "offset generators (a list, unlike the build commands' one --offsets: each is a variant)"},
       technique_option_spec("age-bits"),
       technique_option_spec("block"),
       {"out", "FILE.json|FILE.csv", "", "the rows, JSON or CSV by extension", writes()},
       {"quiet", "", "", "no progress bar (shown on stderr on a terminal)"},
       key_set_option("keys"),
       domain_option(),
       coverage_option(),
       count_option(),
       {"misses", "N", "10000", "(--keys) absent keys looked up per trial"}},
      "  Every variant sees the same streams.\n"
      "  With --keys: the spatial hash's key streams (loads in (0, 1]; --screen, --table, --stream, --spread\n"
      "  and --offsets do not apply): age, reads per hit and per miss, failures, per probing x policy.\n"};
  return spec;
}

namespace {

// --loads: loads in (0, most], UsageError naming the item otherwise (`note` appended).
std::vector<double> parse_loads(const Args& args, double most, const std::string& note) {
  std::vector<double> loads;
  for (const std::string& l : args.list("loads")) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(l.data(), l.data() + l.size(), v);
    if (ec != std::errc() || end != l.data() + l.size() || !(v > 0.0 && v <= most))
      throw UsageError("option --loads: " + excerpt(l) + " is not a load in (0, " + shortest(most) + "]" + note);
    loads.push_back(v);
  }
  return loads;
}

// --screen, --table and --loads: the sizes (the library's rules, validate_experiment).
void parse_experiment_sizes(const Args& args, ExperimentConfig& c) {
  c.screen = args.size("screen");
  c.table = args.extent("table").value_or(c.screen);
  c.loads = parse_loads(args, kMaxExperimentLoad, "");
}

// The experiment of the command line (see stats_spec).
ExperimentConfig parse_experiment(const Args& args) {
  ExperimentConfig c;
  parse_experiment_sizes(args, c);
  c.trials = args.u32_in("trials", 1, 100000);
  c.seed = args.u64_in("seed");
  StreamKind kind = StreamKind::Random;
  try {
    kind = parse_stream_kind(args.str("stream"));
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("option --stream: ") + e.what());
  }
  args.refuse_unless(kind == StreamKind::Stacked, {"spread"}, "on a --stream other than stacked");
  const double spread = args.real("spread");
  if (!(spread >= 0.0 && spread <= 1.0)) throw UsageError("option --spread: must be in [0, 1]");
  c.age_bits = args.u32_in("age-bits", HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  c.block = args.u32_in("block", 1, 1u << 16);
  c.stream = experiment_stream(kind, spread, c.age_bits);
  try {
    validate_experiment(c);  // the message starts with the option's name
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("option --") + e.what());
  }
  c.variants = variant_grid(usage_errors("probing", [&] { return parse_probings(args.list("probing")); }),
                            usage_errors("policy", [&] { return parse_policies(args.list("policy")); }),
                            usage_errors("offsets", [&] { return parse_offset_generators(args.list("offsets")); }));
  return c;
}

void print_rows(const std::vector<ExperimentRow>& rows) {
  std::printf("%-32s %6s %7s %16s %8s %4s %4s %4s %6s %8s %8s %7s %8s\n", "variant", "load", "stored", "mean age (95%)",
              "var", "p50", "p99", "max", "bound", "excess", "probes", "trav", "failed");
  for (const auto& r : rows)
    std::printf("%-32s %6.2f %7.3f %8.3f +- %5.3f %8.3f %4u %4u %4u %6.3f %8.3f %8.3f %7.3f %8llu\n",
                r.variant.name().c_str(), r.load, r.stored_load, r.mean_age, r.mean_age_ci95, r.age_variance, r.p50,
                r.p99, r.max_age, r.rank_bound, r.excess, r.mean_probes, r.traversal_probes,
                static_cast<unsigned long long>(r.failures));
}

}  // namespace

// `habuffer stats --keys SET`: the key-stream experiment (habuffer/key_experiment.h).
int run_key_stats(const Args& args) {
  args.refuse_unless(false, {"screen", "table", "stream", "spread", "offsets"}, "with --keys");
  spatial::KeyExperimentConfig c;
  c.seed = args.u64_in("seed");
  c.keys = parse_key_set(args, "keys", c.seed);
  c.loads = parse_loads(args, 1.0, " (with --keys)");
  c.trials = args.u32_in("trials", 1, 1000);
  c.age_bits = args.u32_in("age-bits", HABUFFER_MIN_AGE_BITS, HABUFFER_MAX_AGE_BITS);
  c.block = args.u32_in("block", 1, 1u << 16);
  c.misses = args.u32_in("misses", 0, 10000000);
  c.probing = usage_errors("probing", [&] { return spatial::parse_key_probings(args.list("probing")); });
  c.policy = usage_errors("policy", [&] { return spatial::parse_key_policies(args.list("policy")); });
  const std::vector<spatial::KeyExperimentRow> rows = spatial::run_key_experiment(c);
  std::printf("%-24s %6s %7s %9s %16s %8s %6s %9s %14s %9s\n", "variant", "load", "stored", "keys", "mean age (95%)",
              "max age", "hit", "miss", "(95%)", "failed");
  for (const auto& r : rows)
    std::printf("%-24s %6.2f %7.3f %9.0f %8.3f +- %5.3f %8.2f %6.3f %9.3f +- %9.3f %9.1f\n", r.variant.c_str(), r.load,
                r.stored_load, r.keys, r.mean_age, r.mean_age_ci95, r.mean_max_age, r.hit_reads, r.miss_reads,
                r.miss_reads_ci95, r.failures);
  if (args.has("out")) {
    const std::string out = args.required("out");
    if (out.size() > 4 && out.substr(out.size() - 4) == ".csv") {
      write_rows_csv(out, rows, key_experiment_columns());
    } else {
      JsonWriter j;
      j.begin_object().field("keys", spatial::to_string(c.keys.set)).field("domain", c.keys.domain.str());
      j.field("trials", c.trials).field("seed", c.seed).field("age_bits", c.age_bits);
      write_rows_json(j, rows, key_experiment_columns());
      j.end_object();
      j.save(out);
    }
  }
  return 0;
}

int run_stats(const std::vector<std::string>& argv) {
  if (print_help(argv, stats_spec())) return 0;
  const Args args(argv, stats_spec());
  if (args.has("keys")) return run_key_stats(args);
  args.refuse_unless(false, {"domain", "coverage", "count", "misses"}, "without --keys");
  ExperimentConfig c = parse_experiment(args);
  std::vector<ExperimentRow> rows;
  {
    ProgressBar progress = ProgressBar::for_terminal("habuffer stats", "trials", args.has("quiet"));
    c.on_progress = progress.callback();
    rows = run_age_experiment(c);
  }
  print_rows(rows);
  if (args.has("out")) {
    const std::string out = args.required("out");
    if (out.size() > 4 && out.substr(out.size() - 4) == ".csv")
      write_rows_csv(out, rows, experiment_columns());
    else
      write_json(out, c, rows);
  }
  return 0;
}

}  // namespace habuffer::cli
