#include "habuffer/gl/gl_spatial_hash.h"

#include <epoxy/gl.h>

#include <stdexcept>
#include <string>

#include "compute_grid.h"
#include "gl_state_guard.h"
#include "gpu_timer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/technique_registry.h"
#include "spatial_glsl.h"

namespace habuffer::gl {
namespace {

constexpr unsigned kResumeLimitPasses = 4096;
constexpr unsigned kLockSpinLimit = 1u << 12;

// The shader of `entry` on the HA-buffer's shared parts: the mode's
// extensions and 64-bit atomics prelude (the modules' own, module_extensions
// and mode_prelude), the shared probe and the spatial hash's GLSL.
std::string source(const GlBindings& bindings, AtomicMode mode, const char* entry) {
  return "#version 450\n" + module_extensions(mode) + bindings.glsl_defines() +
         "#define ha_word uint64_t\n#define ha_index uint\n#define HABUFFER_RECORDS_BINDING HABUFFER_BINDING_TABLE\n"
         "uniform uint habuffer_lock_spin_limit;\n" +
         join_parts({kHaConstants, mode_prelude(mode), kShConstants, kShEnv, kHaProbe, kShSpatial, entry});
}

void set_params(const ShaderProgram& p, const spatial::SpatialKernelParams& k) {
  p.set("sh_age_bits", k.age_bits);
  p.set("ha_table_size", k.table.x, k.table.y);
  p.set("sh_quotient_x", k.quotient_x);
  p.set("ha_max_age_cells_x", k.cells_x);
  p.set("sh_iter_limit", k.iter_limit);
  p.set("sh_block", k.block);
  p.set("habuffer_lock_spin_limit", kLockSpinLimit);
}

void check_size(std::uint64_t bytes, const char* what) {
  if (bytes > max_storage_bytes())
    throw GlError(std::string("spatial hash on the GPU: the ") + what + " takes " + std::to_string(bytes) +
                  " bytes, beyond the driver's " + std::to_string(max_storage_bytes()) + " per shader-storage buffer");
}

AtomicMode mode_for_context(const GlInfo& info) {
  const std::optional<AtomicMode> mode = chosen_atomic_mode(info, Layout::L64);
  if (!mode) throw GlError("spatial hash on the GPU: this context has no 64-bit integers in shaders");
  return *mode;
}

}  // namespace

GlSpatialHash::GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings)
    : GlSpatialHash(table, bindings, query_gl_info()) {}

GlSpatialHash::GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings, const GlInfo& info)
    : bindings_(bindings),
      params_(table.kernel_params()),
      fold_(table.domain()),
      mode_(mode_for_context(info)),
      // GPU timestamps time the shaders, but not on Mesa's software
      // rasterizers (submission times: microseconds for a pass of seconds).
      timed_(!info.software_rasterizer),
      insert_(ShaderProgram::compute(source(bindings_, mode_, kShInsertCompute), "spatial hash insert compute shader")),
      find_(ShaderProgram::compute(source(bindings_, mode_, kShFindCompute), "spatial hash find compute shader")) {
  slot_count_ = table.table().size();
  cell_count_ = table.max_age().size();
  if (slot_count_ > 0xFFFFFFFFull) throw GlError("spatial hash on the GPU: more than 2^32 slots");
  check_size(slot_count_ * 8, "table");
  table_ = GlStorage(slot_count_ * 8, table.table().data());
  max_age_ = GlStorage(cell_count_ * 4, table.max_age().data());
  const std::span<const glm::uvec2> o = table.offsets().values();
  offsets_ = GlStorage(o.size() * sizeof(glm::uvec2), o.data());
  if (mode_ != AtomicMode::Native64) {
    locks_ = GlStorage(((slot_count_ >> 3) + 1) * 4);
    locks_.zero();
  }
}

spatial::InsertReport GlSpatialHash::insert(std::span<const glm::uvec3> keys, std::span<const std::uint32_t> stored,
                                            std::vector<Dropped>& dropped) {
  spatial::InsertReport report;
  report.calls = keys.size();
  resume_passes_ = 0;
  if (keys.empty()) return report;
  const GlStateGuard guard(bindings_);
  std::vector<glm::uvec4> records(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const glm::uvec2 f = fold_.fold(keys[i]);
    records[i] = {f.x, f.y, stored.empty() ? 0u : stored[i], 0u};
  }
  check_size(records.size() * sizeof(glm::uvec4), "records");
  check_size(records.size() * 32, "carries of calls cut short");
  const GlStorage input(records.size() * sizeof(glm::uvec4), records.data());
  GlStorage carries[2] = {GlStorage(records.size() * 32), GlStorage(records.size() * 32)};
  const GlStorage drops(records.size() * 16);
  const GlStorage counters(16 * 4);
  counters.zero();
  bind_table();
  drops.bind_storage(bindings_.capture);
  counters.bind_storage(bindings_.counters);
  glUseProgram(insert_.id());
  set_params(insert_, params_);
  std::uint64_t pending = records.size();
  for (unsigned pass = 0;; ++pass) {
    (pass == 0 ? input : carries[pass % 2]).bind_storage(bindings_.stream);  // records, or the cut calls to resume
    carries[(pass + 1) % 2].bind_storage(bindings_.deferred);              // the calls this pass cuts short
    insert_.set("sh_count", static_cast<unsigned>(pending));
    insert_.set("sh_resume", pass == 0 ? 0u : 1u);
    const GpuTimer timer;
    timer.begin();
    dispatch_grid(pending, 64);
    timer.end();
    gpu_ms_ = timed_ ? (pass == 0 ? 0.0 : gpu_ms_) + timer.milliseconds() : 0.0;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> c = counters.read_words(16);
    pending = c[8];
    if (pending == 0) break;
    if (pass + 1 >= kResumeLimitPasses)
      throw GlError("spatial hash on the GPU: " + std::to_string(pending) + " calls still cut short after " +
                    std::to_string(kResumeLimitPasses) + " passes");
    ++resume_passes_;
    const std::uint32_t zero = 0;
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, counters.id());
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 8 * 4, 4, &zero);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  }
  const std::vector<std::uint32_t> c = counters.read_words(16);
  report.stored = std::uint64_t{c[HABUFFER_SH_STORED]} + c[HABUFFER_SH_REVIVED] + c[HABUFFER_SH_STORED_TOMBSTONE_DROPPED];
  report.tombstones_dropped = std::uint64_t{c[HABUFFER_SH_REVIVED]} + c[HABUFFER_SH_STORED_TOMBSTONE_DROPPED];
  report.duplicates = c[HABUFFER_SH_DUPLICATE];
  report.failed_age = c[HABUFFER_SH_FAILED_AGE];
  report.failed_iter = c[HABUFFER_SH_FAILED_ITER];
  const std::vector<glm::uvec4> d = drops.read<glm::uvec4>(c[9]);
  for (const glm::uvec4& r : d) dropped.push_back({fold_.unfold({r.x, r.y}), r.z});
  return report;
}

std::uint64_t GlSpatialHash::find(std::span<const glm::uvec3> keys, std::span<std::uint32_t> stored,
                                  std::span<std::uint8_t> found) const {
  if (keys.empty()) return 0;
  const GlStateGuard guard(bindings_);
  std::vector<glm::uvec2> folded(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) folded[i] = fold_.fold(keys[i]);
  check_size(folded.size() * 8, "queries");
  const GlStorage queries(folded.size() * 8, folded.data());
  const GlStorage answers(folded.size() * 8);
  bind_table();
  queries.bind_storage(bindings_.stream);
  answers.bind_storage(bindings_.capture);
  glUseProgram(find_.id());
  set_params(find_, params_);
  find_.set("sh_count", static_cast<unsigned>(folded.size()));
  const GpuTimer timer;
  timer.begin();
  dispatch_grid(folded.size(), 64);
  timer.end();
  gpu_ms_ = timed_ ? timer.milliseconds() : 0.0;
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::vector<glm::uvec2> a = answers.read<glm::uvec2>(folded.size());
  std::uint64_t hits = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    found[i] = a[i].x != 0u ? 1u : 0u;
    stored[i] = a[i].y;
    hits += a[i].x;
  }
  return hits;
}

void GlSpatialHash::bind_table() const {
  table_.bind_storage(bindings_.table);
  max_age_.bind_storage(bindings_.max_age);
  offsets_.bind_storage(bindings_.offsets);
  locks_.bind_storage(bindings_.locks);
}

void GlSpatialHash::clear() {
  table_.zero();
  max_age_.zero();
}

std::vector<std::uint64_t> GlSpatialHash::slots() const { return table_.read<std::uint64_t>(slot_count_); }
std::vector<std::uint32_t> GlSpatialHash::max_age() const { return max_age_.read<std::uint32_t>(cell_count_); }

spatial::InsertReport gl_insert(spatial::SpatialHash& table, std::span<const glm::uvec3> keys,
                                std::span<const std::uint32_t> values) {
  const spatial::SpatialHashConfig c = table.config();
  if (c.rule == spatial::DuplicateRule::First || c.rule == spatial::DuplicateRule::Last)
    throw std::invalid_argument("spatial hash on the GPU: rule " + to_string(c.rule) +
                                " orders a batch, which concurrent GPU calls do not: use max or min, or the CPU path");
  if (!values.empty() && values.size() != keys.size())
    throw std::invalid_argument("spatial hash: " + std::to_string(keys.size()) + " keys but " +
                                std::to_string(values.size()) + " values");
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (!table.domain().contains(keys[i]))
      throw std::invalid_argument("spatial hash: key " + std::to_string(i) + " (" + std::to_string(keys[i].x) + ", " +
                                  std::to_string(keys[i].y) + ", " + std::to_string(keys[i].z) +
                                  ") is outside the domain " + c.domain.str());
  const std::uint64_t slots_before = table.slots();
  if (c.adaptive &&
      static_cast<double>(table.size() + table.tombstones() + keys.size()) > c.grow_at * static_cast<double>(table.slots()))
    table.reserve(table.size() + keys.size(), c.target_load);
  std::vector<std::uint32_t> stored(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::uint32_t v = values.empty() ? 0u : values[i];
    stored[i] = c.rule == spatial::DuplicateRule::Min ? ~v : v;
  }
  GlSpatialHash gpu(table);
  std::vector<GlSpatialHash::Dropped> dropped;
  spatial::InsertReport report = gpu.insert(keys, stored, dropped);
  if (table.slots() != slots_before) ++report.rehashes;
  table = spatial::SpatialHash::restore(c, table.table_extent(), gpu.slots(), gpu.max_age());
  if (!dropped.empty()) {
    // The failed calls' records, again on the CPU after growing (lossless).
    std::vector<glm::uvec3> k;
    std::vector<std::uint32_t> v;
    for (const GlSpatialHash::Dropped& d : dropped) {
      k.push_back(d.key);
      v.push_back(c.rule == spatial::DuplicateRule::Min ? ~d.stored : d.stored);
    }
    if (!c.lossless) {
      report.lost += dropped.size();
    } else {
      const spatial::InsertReport again = table.insert(k, v);
      report.rehashes += again.rehashes;
      report.lost += again.lost;
    }
  }
  return report;
}

}  // namespace habuffer::gl
