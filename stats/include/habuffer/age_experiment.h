/// @file
/// Experiments on age vs load: every variant (probing, policy, offsets) runs
/// on the same streams, trial by trial, and each (variant, load) gets its age
/// statistics with a 95% confidence interval over trials, so differences
/// between variants are measured on equal inputs and reported with their noise.
#pragma once

#include <algorithm>

#include <cstdint>
#include <functional>
#include <string>
#include <span>
#include <vector>

#include "habuffer/fragment_streams.h"
#include "habuffer/probe_simulator.h"

namespace habuffer {

/// One insertion model to compare.
struct Variant {
  Probing probing = Probing::Coherent;                ///< probe sequence
  Policy policy = Policy::RobinHood;                  ///< placement
  OffsetGenerator offsets = OffsetGenerator::Random;  ///< coherent probing's offsets
  [[nodiscard]] std::string name() const;  ///< e.g. "coherent/robinhood/random"
};

/// What run_age_experiment runs.
struct ExperimentConfig {
  Extent screen{128, 128};      ///< pixels (not empty)
  Extent table;                 ///< zero: the screen
  std::vector<double> loads{0.5, 0.8, 0.9};  ///< fragments = load * table slots
  std::uint32_t trials = 5;     ///< streams per load (at least 1)
  std::uint64_t seed = 1;       ///< trial t's stream seed: seed * 1000003 + t
  StreamOptions stream{.kind = StreamKind::Random};  ///< kind and shape; count and seed are set per trial
  std::vector<Variant> variants{Variant{}};  ///< each run on every trial's stream
  std::uint32_t age_bits = 8;   ///< as SimulatorConfig
  std::uint32_t block = 8;      ///< as SimulatorConfig
  /// Called after each trial of each load with (trials done, loads x trials).
  std::function<void(std::uint64_t, std::uint64_t)> on_progress;
};

/// The largest load an experiment takes: 4 records per slot (beyond, every
/// variant only fails).
inline constexpr double kMaxExperimentLoad = 4.0;

/// Throws std::invalid_argument, the message starting with the field's name
/// (a caller prefixes its option syntax): no trials, an empty screen, a
/// table with a zero side or smaller than the screen, a load outside (0, 4]
/// or giving no fragment, or a table and stream beyond the machine's memory.
void validate_experiment(const ExperimentConfig& config);

/// One (variant, load)'s statistics over the trials.
struct ExperimentRow {
  Variant variant;               ///< the variant measured
  double load = 0.0;             ///< target load
  double stored_load = 0.0;      ///< mean measured load (stored / slots)
  std::uint32_t trials = 0;      ///< trials measured
  double mean_age = 0.0;         ///< mean over trials of each trial's mean age of stored records
  double mean_age_ci95 = 0.0;    ///< half-width, Student t over trials
  double age_variance = 0.0;     ///< of all stored records' ages, pooled over trials
  std::uint32_t p50 = 0, p90 = 0, p99 = 0, max_age = 0;  ///< quantiles and largest of the pooled ages
  double mean_max_age = 0.0;     ///< mean over trials of each trial's largest age
  double mean_max_age_ci95 = 0.0;  ///< half-width, Student t over trials
  double rank_bound = 0.0;       ///< least possible mean age: a pixel's k-th record has age >= k
  double excess_ci95 = 0.0;      ///< half-width of mean_age - rank_bound over trials
  double excess = 0.0;           ///< mean over trials of (mean age - rank bound)
  double mean_probes = 0.0;      ///< per insert call
  std::uint32_t max_probes = 0;  ///< most slots one insert call probed, over all trials
  double traversal_probes = 0.0;         ///< per screen pixel
  double wasted_traversal_probes = 0.0;  ///< per screen pixel, read after its last record
  std::uint64_t failures = 0;            ///< failed_age + failed_iter over all trials
};

/// The experiments' variant lists by name, "all" for every one, in the
/// given order without repeats: "coherent", "independent"; "robinhood",
/// "fcfs"; "random", "farthest". Throw std::invalid_argument "unknown value
/// 'X' (names or all)".
std::vector<Probing> parse_probings(const std::vector<std::string>& names);
std::vector<Policy> parse_policies(const std::vector<std::string>& names);  ///< see parse_probings
std::vector<OffsetGenerator> parse_offset_generators(const std::vector<std::string>& names);  ///< see parse_probings

/// Every combination of the lists, in their order (probing, then policy,
/// then offsets), the offsets varied under coherent probing only (the
/// independent probe has none): habuffer stats' and the Python module's variants.
std::vector<Variant> variant_grid(const std::vector<Probing>& probings, const std::vector<Policy>& policies,
                                  const std::vector<OffsetGenerator>& offsets);
/// The experiments' stream of `kind`: stacked quads pulled together by
/// `spread`, hot pixels as deep as AMAX of `age_bits` (deep enough to fill a
/// probe sequence, no deeper).
StreamOptions experiment_stream(StreamKind kind, double spread, std::uint32_t age_bits);

/// One row per load and variant, load by load, variants in their order. Throws std::invalid_argument for no trials, an
/// empty screen, a table with a zero side or a load that is not positive (and as ProbeSimulator).
std::vector<ExperimentRow> run_age_experiment(const ExperimentConfig& config);

/// Running mean, variance and the 95% confidence half-width of samples
/// added one at a time (the experiments' per-trial statistics).
struct Moments {
  double n = 0, sum = 0, sum2 = 0;
  void add(double v) {  ///< one sample
    n += 1;
    sum += v;
    sum2 += v * v;
  }
  [[nodiscard]] double mean() const { return n > 0 ? sum / n : 0.0; }  ///< 0 without samples
  /// The sample variance (0 below two samples; never negative from rounding).
  [[nodiscard]] double variance() const { return n > 1 ? std::max(0.0, (sum2 - sum * sum / n) / (n - 1)) : 0.0; }
  /// Student t95(n - 1) * s / sqrt(n); 0 below two samples.
  [[nodiscard]] double ci95() const;
};

/// Two-sided 95% Student t quantile for `df` degrees of freedom: tabulated to 30, then within 0.002 of it;
/// infinite for 0.
double student_t95(std::uint32_t df);

/// Half-width of the 95% confidence interval of the mean of `samples`:
/// t95(n - 1) * s / sqrt(n), with s the sample standard deviation; 0 for
/// fewer than two samples.
double mean_ci95(std::span<const double> samples);

}  // namespace habuffer
