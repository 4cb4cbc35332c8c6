#include "habuffer/experiment_columns.h"

#include <cstdio>

namespace habuffer {
namespace {

using A = ExperimentRow;
using K = spatial::KeyExperimentRow;

ColumnValue count(std::uint64_t v) { return v; }

constexpr RowColumn<A> kExperimentColumns[] = {
    {"variant", "", [](const A& r) { return ColumnValue{r.variant.name()}; }},
    {"load", "%g", [](const A& r) { return ColumnValue{r.load}; }},
    {"stored_load", "%.6f", [](const A& r) { return ColumnValue{r.stored_load}; }},
    {"trials", "", [](const A& r) { return count(r.trials); }},
    {"mean_age", "%.6f", [](const A& r) { return ColumnValue{r.mean_age}; }},
    {"mean_age_ci95", "%.6f", [](const A& r) { return ColumnValue{r.mean_age_ci95}; }},
    {"age_variance", "%.6f", [](const A& r) { return ColumnValue{r.age_variance}; }},
    {"p50", "", [](const A& r) { return count(r.p50); }},
    {"p90", "", [](const A& r) { return count(r.p90); }},
    {"p99", "", [](const A& r) { return count(r.p99); }},
    {"max_age", "", [](const A& r) { return count(r.max_age); }},
    {"mean_max_age", "%.4f", [](const A& r) { return ColumnValue{r.mean_max_age}; }},
    {"mean_max_age_ci95", nullptr, [](const A& r) { return ColumnValue{r.mean_max_age_ci95}; }},
    {"rank_bound", "%.6f", [](const A& r) { return ColumnValue{r.rank_bound}; }},
    {"excess", "%.6f", [](const A& r) { return ColumnValue{r.excess}; }},
    {"excess_ci95", "%.6f", [](const A& r) { return ColumnValue{r.excess_ci95}; }},
    {"mean_probes", "%.6f", [](const A& r) { return ColumnValue{r.mean_probes}; }},
    {"max_probes", "", [](const A& r) { return count(r.max_probes); }},
    {"traversal_probes", "%.6f", [](const A& r) { return ColumnValue{r.traversal_probes}; }},
    {"wasted_traversal_probes", "%.6f", [](const A& r) { return ColumnValue{r.wasted_traversal_probes}; }},
    {"failures", "", [](const A& r) { return count(r.failures); }},
};

constexpr RowColumn<K> kKeyExperimentColumns[] = {
    {"variant", "", [](const K& r) { return ColumnValue{r.variant}; }},
    {"load", "%g", [](const K& r) { return ColumnValue{r.load}; }},
    {"stored_load", "%.6f", [](const K& r) { return ColumnValue{r.stored_load}; }},
    {"trials", "", [](const K& r) { return count(r.trials); }},
    {"keys", "%.1f", [](const K& r) { return ColumnValue{r.keys}; }},
    {"mean_age", "%.6f", [](const K& r) { return ColumnValue{r.mean_age}; }},
    {"mean_age_ci95", "%.6f", [](const K& r) { return ColumnValue{r.mean_age_ci95}; }},
    {"mean_max_age", "%.6f", [](const K& r) { return ColumnValue{r.mean_max_age}; }},
    {"max_age", "", [](const K& r) { return count(r.max_age); }},
    {"hit_reads", "%.6f", [](const K& r) { return ColumnValue{r.hit_reads}; }},
    {"miss_reads", "%.6f", [](const K& r) { return ColumnValue{r.miss_reads}; }},
    {"miss_reads_ci95", "%.6f", [](const K& r) { return ColumnValue{r.miss_reads_ci95}; }},
    {"failures", "%.4f", [](const K& r) { return ColumnValue{r.failures}; }},
};

}  // namespace

std::span<const RowColumn<ExperimentRow>> experiment_columns() { return kExperimentColumns; }
std::span<const RowColumn<spatial::KeyExperimentRow>> key_experiment_columns() { return kKeyExperimentColumns; }

std::string csv_cell(const ColumnValue& value, const char* format) {
  if (const auto* text = std::get_if<std::string>(&value)) return *text;
  if (const auto* n = std::get_if<std::uint64_t>(&value)) return std::to_string(*n);
  char buf[64];
  std::snprintf(buf, sizeof buf, (format && *format) ? format : "%.17g", std::get<double>(value));
  return buf;
}

}  // namespace habuffer
