// The spatial hash against the CPU tables people use (issue 22): builds,
// hits and misses per second on the same keys, at our loads 0.5 .. 0.99 and
// the peers' own, with bytes per key. Run interleaved:
//   habuffer_bench --benchmark_filter=Spatial --benchmark_enable_random_interleaving=true
//     --benchmark_repetitions=3
// Keys: the sparse image of Coherent Parallel Hashing's demo (2048^2, 25 %
// of the pixels in discs) and a voxel sphere's shell (512^3), packed into
// 32-bit integers for the peers (y * W + x; z * W * H added for voxels).
// Peers are built only where found: absl::flat_hash_map (libabsl-dev),
// google::dense_hash_map (libsparsehash-dev), std::unordered_map.
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdint>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "bench_common.h"
#include "habuffer/gl/gl_spatial_hash.h"
#include "habuffer/key_streams.h"
#include "habuffer/spatial/spatial_hash.h"

#if HABUFFER_HAVE_ABSL
#include <absl/container/flat_hash_map.h>
#endif
#if HABUFFER_HAVE_SPARSEHASH
#include <sparsehash/dense_hash_map>
#endif

namespace habuffer::spatial {
namespace {

struct Dataset {
  std::string name;
  Domain domain;
  std::vector<glm::uvec3> keys;                         // row-major
  std::vector<std::uint32_t> values;
  std::map<KeyOrder, std::vector<glm::uvec3>> queries;  // the keys in each order
  std::vector<glm::uvec3> absent;                       // shuffled
  std::vector<glm::uvec3> absent_row_major;             // the same, row-major
  std::vector<glm::uvec3> neighbours;                   // each key's 6 face neighbours, row-major by key
};

std::uint32_t packed(const Domain& d, glm::uvec3 k) { return k.x + d.x * (k.y + d.y * k.z); }

const Dataset& dataset(const std::string& name) {
  static std::map<std::string, Dataset> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  Dataset s;
  s.name = name;
  KeySetOptions o;
  if (name == "image") {
    o.set = KeySet::SparseImage;
    o.domain = {2048, 2048, 1};
  } else {
    o.set = KeySet::VoxelShell;
    o.domain = {512, 512, 512};
  }
  s.domain = o.domain;
  s.keys = make_keys(o);
  s.values.resize(s.keys.size());
  for (std::size_t i = 0; i < s.keys.size(); ++i) s.values[i] = static_cast<std::uint32_t>(i * 2654435761u);
  for (const KeyOrder order : {KeyOrder::RowMajor, KeyOrder::Morton, KeyOrder::RandomWalk, KeyOrder::Shuffled})
    s.queries[order] = ordered(s.keys, order, 3);
  s.absent = absent_keys(s.keys, s.domain, s.keys.size(), 5);
  s.absent_row_major = ordered(s.absent, KeyOrder::RowMajor, 0);
  for (const glm::uvec3 k : s.keys)
    for (const glm::ivec3 step : {glm::ivec3(-1, 0, 0), glm::ivec3(1, 0, 0), glm::ivec3(0, -1, 0),
                                  glm::ivec3(0, 1, 0), glm::ivec3(0, 0, -1), glm::ivec3(0, 0, 1)}) {
      const glm::ivec3 n = glm::ivec3(k) + step;
      if (n.x < 0 || n.y < 0 || n.z < 0) continue;
      const glm::uvec3 u(n);
      if (u.x < s.domain.x && u.y < s.domain.y && u.z < s.domain.z) s.neighbours.push_back(u);
    }
  return cache.emplace(name, std::move(s)).first->second;
}

using Queries = const std::vector<glm::uvec3>& (*)(const Dataset&);

SpatialHash ours(const Dataset& s, double load, std::uint32_t threads) {
  SpatialHashConfig c;
  c.domain = s.domain;
  c.adaptive = false;
  c.threads = threads;
  c.rule = DuplicateRule::Max;  // the keys are distinct: no rule work
  SpatialHash h(c);
  h.reserve(s.keys.size(), load);
  return h;
}

void set_counters(benchmark::State& state, std::size_t items, double bytes_per_key, double load) {
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()) * static_cast<std::int64_t>(items));
  state.counters["bytes_per_key"] = bytes_per_key;
  state.counters["load"] = load;
}

// --- ours ------------------------------------------------------------------

void ours_build(benchmark::State& state, std::string name, double load, std::uint32_t threads) {
  const Dataset& s = dataset(name);
  SpatialHash h = ours(s, load, threads);
  for (auto _ : state) {
    state.PauseTiming();
    h.clear();
    state.ResumeTiming();
    h.insert(s.keys, s.values);
  }
  set_counters(state, s.keys.size(), h.stats().bytes_per_key, h.load());
}

// Slots a lookup reads, on average over the queries (SpatialHash::probes).
double slots_per_query(const SpatialHash& h, const std::vector<glm::uvec3>& q) {
  double sum = 0;
  for (const glm::uvec3 k : q) sum += h.probes(k);
  return q.empty() ? 0.0 : sum / static_cast<double>(q.size());
}

void ours_find(benchmark::State& state, std::string name, double load, const std::vector<glm::uvec3>& (*queries)(const Dataset&),
               std::uint32_t filter_bits) {
  const Dataset& s = dataset(name);
  SpatialHash h = ours(s, load, 2);
  h.insert(s.keys, s.values);
  h.set_miss_filter(filter_bits);
  const SpatialHashView v = h.view();
  const std::vector<glm::uvec3>& q = queries(s);
  for (auto _ : state) {
    std::uint64_t sum = 0;
    for (const glm::uvec3 k : q) sum += v.find(k).value_or(1u);
    benchmark::DoNotOptimize(sum);
  }
  set_counters(state, q.size(), h.stats().bytes_per_key, h.load());
  state.counters["slots_per_query"] = slots_per_query(h, q);
}

// --- the miss filter's candidates (issue 36) ----------------------------------
// Each candidate answers "absent" from its own structure, built from the
// table's records, or passes the key on to the table's lookup without a
// filter. Timed on the misses (the structure's bytes counted in the bytes per
// key); `passed` is the share of queries the candidate could not answer.
enum class MissCandidate { Occupancy, Fingerprint };

void miss_candidate(benchmark::State& state, std::string name, double load, Queries queries, MissCandidate what) {
  const Dataset& s = dataset(name);
  SpatialHash h = ours(s, load, 2);
  h.insert(s.keys, s.values);
  h.set_miss_filter(0);
  SpatialHashKernel<false> k(h.kernel_params(), h.offsets().values().data(),
                             const_cast<std::uint64_t*>(h.table().data()),
                             const_cast<std::uint32_t*>(h.max_age().data()), nullptr);
  const Extent t = h.table_extent();
  const std::uint32_t cells_x = (t.x + 7) / 8;
  // Occupancy: one bit a position, 64 to a word per 8 x 8 block (a key's
  // position holds some record's key). Fingerprint: one byte a position,
  // bit (hash of the quotient) mod 8 of every key there.
  std::vector<std::uint64_t> occupancy(std::uint64_t{cells_x} * ((t.y + 7) / 8), 0);
  std::vector<std::uint8_t> fingerprint(t.area(), 0);
  const auto fp_bit = [](std::uint32_t q) { return static_cast<std::uint8_t>(1u << ((q * 0x9E3779B1u) >> 29)); };
  for (std::uint64_t slot = 0; slot < h.table().size(); ++slot) {
    const std::uint64_t r = h.table()[slot];
    if (r == 0) continue;
    const glm::uvec2 p = k.sh_position(k.sh_record_key(slot, r));
    occupancy[(p.x >> 3) + (p.y >> 3) * std::uint64_t{cells_x}] |= std::uint64_t{1} << ((p.x & 7u) | (p.y & 7u) << 3);
    fingerprint[p.x + std::uint64_t{p.y} * t.x] |= fp_bit(k.sh_quotient(r));
  }
  const SpatialHashView v = h.view();
  const std::vector<glm::uvec3>& q = queries(s);
  const FoldedDomain& fold = h.domain();
  std::uint64_t passed = 0;
  for (auto _ : state) {
    std::uint64_t sum = 0, pass = 0;
    for (const glm::uvec3 key : q) {
      const glm::uvec2 f = fold.fold(key), p = k.sh_position(f);
      const bool maybe =
          what == MissCandidate::Occupancy
              ? (occupancy[(p.x >> 3) + (p.y >> 3) * std::uint64_t{cells_x}] >> ((p.x & 7u) | (p.y & 7u) << 3) & 1u) != 0
              : (fingerprint[p.x + std::uint64_t{p.y} * t.x] & fp_bit(k.sh_key_quotient(f))) != 0;
      if (!maybe) {
        sum += 1;
        continue;
      }
      ++pass;
      sum += v.find(key).value_or(1u);
    }
    passed = pass;
    benchmark::DoNotOptimize(sum);
  }
  const double extra = what == MissCandidate::Occupancy ? static_cast<double>(occupancy.size() * 8)
                                                        : static_cast<double>(fingerprint.size());
  set_counters(state, q.size(), (static_cast<double>(h.memory_bytes()) + extra) / static_cast<double>(h.size()), h.load());
  state.counters["passed"] = static_cast<double>(passed) / static_cast<double>(q.size());
}

void ours_find_batch(benchmark::State& state, std::string name, double load, std::uint32_t threads, Queries queries) {
  const Dataset& s = dataset(name);
  SpatialHash h = ours(s, load, threads);
  h.insert(s.keys, s.values);
  const std::vector<glm::uvec3>& q = queries(s);
  std::vector<std::uint32_t> values(q.size());
  std::vector<std::uint8_t> found(q.size());
  for (auto _ : state) benchmark::DoNotOptimize(h.find(q, values, found));
  set_counters(state, q.size(), h.stats().bytes_per_key, h.load());
}

// --- ours on the GPU (GL compute; GPU time of the passes, no transfers) -------

// The passes' GPU time, or the call's wall time (uploads and read-backs
// included) where the driver times nothing (llvmpipe's GL_TIME_ELAPSED is 0):
// `gpu_timed` becomes 0 then.
double seconds(double gpu_ms, std::chrono::steady_clock::time_point t0, double& gpu_timed) {
  if (gpu_ms > 0.0) return gpu_ms * 1e-3;
  gpu_timed = 0.0;
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void gl_build(benchmark::State& state, std::string name, double load) {
  bench::gl_bench_context();
  const Dataset& s = dataset(name);
  SpatialHash h = ours(s, load, 2);
  gl::GlSpatialHash gpu(h);
  std::vector<gl::GlSpatialHash::Dropped> dropped;
  double gpu_timed = 1.0;
  for (auto _ : state) {
    gpu.clear();
    dropped.clear();
    const auto t0 = std::chrono::steady_clock::now();
    gpu.insert(s.keys, s.values, dropped);
    state.SetIterationTime(seconds(gpu.gpu_ms(), t0, gpu_timed));
  }
  state.counters["gpu_timed"] = gpu_timed;
  state.counters["dropped"] = static_cast<double>(dropped.size());
  state.counters["resume_passes"] = gpu.resume_passes();
  set_counters(state, s.keys.size(), static_cast<double>(h.memory_bytes()) / static_cast<double>(s.keys.size()), load);
}

void gl_find(benchmark::State& state, std::string name, double load, Queries queries) {
  bench::gl_bench_context();
  const Dataset& s = dataset(name);
  SpatialHash h = ours(s, load, 2);
  h.insert(s.keys, s.values);
  const gl::GlSpatialHash gpu(h);
  const std::vector<glm::uvec3>& q = queries(s);
  std::vector<std::uint32_t> values(q.size());
  std::vector<std::uint8_t> found(q.size());
  double gpu_timed = 1.0;
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    benchmark::DoNotOptimize(gpu.find(q, values, found));
    state.SetIterationTime(seconds(gpu.gpu_ms(), t0, gpu_timed));
  }
  state.counters["gpu_timed"] = gpu_timed;
  set_counters(state, q.size(), h.stats().bytes_per_key, h.load());
}

// --- peers: Map with insert_or_assign / find on packed 32-bit keys ------------

template <class Map>
double bytes_per_key(const Map& m);

template <class Map>
Map make_peer() {
  return Map();
}

#if HABUFFER_HAVE_ABSL
using Absl = absl::flat_hash_map<std::uint32_t, std::uint32_t>;
template <>
double bytes_per_key(const Absl& m) {
  // One slot (the pair) and one control byte per bucket.
  return static_cast<double>(m.bucket_count() * (sizeof(Absl::slot_type) + 1)) / static_cast<double>(m.size());
}
#endif
#if HABUFFER_HAVE_SPARSEHASH
using Dense = google::dense_hash_map<std::uint32_t, std::uint32_t>;
template <>
Dense make_peer() {
  Dense m;
  m.set_empty_key(0xFFFFFFFFu);
  return m;
}
template <>
double bytes_per_key(const Dense& m) {
  return static_cast<double>(m.bucket_count() * sizeof(std::pair<const std::uint32_t, std::uint32_t>)) /
         static_cast<double>(m.size());
}
#endif
using Std = std::unordered_map<std::uint32_t, std::uint32_t>;
template <>
double bytes_per_key(const Std& m) {
  // A bucket pointer each, and a node per key (next pointer and the pair, as
  // glibc's malloc rounds 16 bytes of payload: 32 bytes).
  return static_cast<double>(m.bucket_count() * sizeof(void*) + m.size() * 32) / static_cast<double>(m.size());
}

// Room for n keys: reserve(), or dense_hash_map's resize().
template <class Map>
void make_room(Map& m, std::size_t n) {
  if constexpr (requires { m.reserve(n); }) m.reserve(n);
  else m.resize(n);
}

template <class Map>
double peer_load(const Map& m) {
  return static_cast<double>(m.size()) / static_cast<double>(m.bucket_count());
}

template <class Map>
Map filled(const Dataset& s) {
  Map m = make_peer<Map>();
  make_room(m, s.keys.size());
  for (std::size_t i = 0; i < s.keys.size(); ++i) m[packed(s.domain, s.keys[i])] = s.values[i];
  return m;
}

template <class Map>
void peer_build(benchmark::State& state, std::string name) {
  const Dataset& s = dataset(name);
  std::vector<std::uint32_t> packed_keys(s.keys.size());
  for (std::size_t i = 0; i < s.keys.size(); ++i) packed_keys[i] = packed(s.domain, s.keys[i]);
  double bpk = 0, load = 0;
  for (auto _ : state) {
    Map m = make_peer<Map>();
    make_room(m, s.keys.size());
    for (std::size_t i = 0; i < packed_keys.size(); ++i) m[packed_keys[i]] = s.values[i];
    state.PauseTiming();
    bpk = bytes_per_key(m);
    load = peer_load(m);
    state.ResumeTiming();
  }
  set_counters(state, s.keys.size(), bpk, load);
}

template <class Map>
void peer_find(benchmark::State& state, std::string name, const std::vector<glm::uvec3>& (*queries)(const Dataset&)) {
  const Dataset& s = dataset(name);
  const Map m = filled<Map>(s);
  const std::vector<glm::uvec3>& q = queries(s);
  std::vector<std::uint32_t> packed_q(q.size());
  for (std::size_t i = 0; i < q.size(); ++i) packed_q[i] = packed(s.domain, q[i]);
  for (auto _ : state) {
    std::uint64_t sum = 0;
    for (const std::uint32_t k : packed_q) {
      const auto it = m.find(k);
      sum += it == m.end() ? 1u : it->second;
    }
    benchmark::DoNotOptimize(sum);
  }
  set_counters(state, q.size(), bytes_per_key(m), peer_load(m));
}

// --- registration ------------------------------------------------------------

const std::vector<glm::uvec3>& by_row(const Dataset& s) { return s.queries.at(KeyOrder::RowMajor); }
const std::vector<glm::uvec3>& by_morton(const Dataset& s) { return s.queries.at(KeyOrder::Morton); }
const std::vector<glm::uvec3>& by_walk(const Dataset& s) { return s.queries.at(KeyOrder::RandomWalk); }
const std::vector<glm::uvec3>& by_shuffle(const Dataset& s) { return s.queries.at(KeyOrder::Shuffled); }
const std::vector<glm::uvec3>& misses(const Dataset& s) { return s.absent; }
const std::vector<glm::uvec3>& misses_row_major(const Dataset& s) { return s.absent_row_major; }
const std::vector<glm::uvec3>& neighbours(const Dataset& s) { return s.neighbours; }

template <class Map>
void register_peer(const std::string& label, const std::string& set,
                   const std::vector<std::pair<std::string, Queries>>& finds) {
  benchmark::RegisterBenchmark(("BM_Spatial/" + set + "/build/" + label).c_str(), peer_build<Map>, set)
      ->Unit(benchmark::kMillisecond)
      ->MinTime(0.2);
  for (const auto& [what, q] : finds)
    benchmark::RegisterBenchmark(("BM_Spatial/" + set + "/" + what + "/" + label).c_str(), peer_find<Map>, set, q)
        ->Unit(benchmark::kMillisecond)
        ->MinTime(0.2);
}

int register_all() {
  for (const std::string set : {"image", "shell"}) {
    std::vector<std::pair<std::string, Queries>> finds = {{"hits-row-major", by_row},
                                                          {"hits-morton", by_morton},
                                                          {"hits-random-walk", by_walk},
                                                          {"hits-shuffled", by_shuffle},
                                                          {"misses", misses},
                                                          {"misses-row-major", misses_row_major}};
    if (set == "shell") finds.emplace_back("neighbours", neighbours);
    for (const double load : {0.5, 0.8, 0.9, 0.95, 0.99}) {
      const std::string l = "ours-load-" + std::to_string(load).substr(0, 4);
      for (const std::uint32_t threads : {1u, 2u})
        benchmark::RegisterBenchmark(("BM_Spatial/" + set + "/build/" + l + "/threads-" + std::to_string(threads)).c_str(),
                                     ours_build, set, load, threads)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.2)
            ->UseRealTime();
      for (const auto& [what, q] : finds) {
        benchmark::RegisterBenchmark(("BM_Spatial/" + set + "/" + what + "/" + l).c_str(), ours_find, set, load, q,
                                     HABUFFER_SH_DEFAULT_FILTER_BITS)
            ->Unit(benchmark::kMillisecond)
            ->MinTime(0.2);
        // Issue 36: the same lookups with the miss filter at 8 bits a slot
        // and without it, and the filter's candidates, at our load 0.95.
        if (load != 0.95) continue;
        for (const auto& [label, bits] : {std::pair{"filter-8", 8u}, std::pair{"no-filter", 0u}})
          benchmark::RegisterBenchmark(("BM_Spatial/" + set + "/" + what + "/" + l + "/" + label).c_str(), ours_find,
                                       set, load, q, bits)
              ->Unit(benchmark::kMillisecond)
              ->MinTime(0.2);
        if (what.starts_with("hits")) continue;
        for (const auto& [label, c] : {std::pair{"occupancy", MissCandidate::Occupancy},
                                       std::pair{"fingerprint", MissCandidate::Fingerprint}})
          benchmark::RegisterBenchmark(("BM_Spatial/" + set + "/" + what + "/" + l + "/candidate-" + label).c_str(),
                                       miss_candidate, set, load, q, c)
              ->Unit(benchmark::kMillisecond)
              ->MinTime(0.2);
      }
      for (const auto& [what, q] : finds)
        for (const std::uint32_t threads : {1u, 2u})
          benchmark::RegisterBenchmark(
              ("BM_Spatial/" + set + "/" + what + "/" + l + "/batch-threads-" + std::to_string(threads)).c_str(),
              ours_find_batch, set, load, threads, q)
              ->Unit(benchmark::kMillisecond)
              ->MinTime(0.2)
              ->UseRealTime();
    }
    // The GPU path at the loads of BGHT's and CPH's published rates.
    for (const double load : {0.8, 0.99}) {
      const std::string l = "gl-load-" + std::to_string(load).substr(0, 4);
      benchmark::RegisterBenchmark(("BM_GlSpatial/" + set + "/build/" + l).c_str(), gl_build, set, load)
          ->Unit(benchmark::kMillisecond)
          ->UseManualTime()
          ->MinTime(0.2);
      for (const auto& [what, q] : finds)
        if (what == "hits-row-major" || what == "hits-shuffled" || what == "misses")
          benchmark::RegisterBenchmark(("BM_GlSpatial/" + set + "/" + what + "/" + l).c_str(), gl_find, set, load, q)
              ->Unit(benchmark::kMillisecond)
              ->UseManualTime()
              ->MinTime(0.2);
    }
#if HABUFFER_HAVE_ABSL
    register_peer<Absl>("absl-flat-hash-map", set, finds);
#endif
#if HABUFFER_HAVE_SPARSEHASH
    register_peer<Dense>("dense-hash-map", set, finds);
#endif
    register_peer<Std>("std-unordered-map", set, finds);
  }
  return 0;
}

const int registered = register_all();

}  // namespace
}  // namespace habuffer::spatial
