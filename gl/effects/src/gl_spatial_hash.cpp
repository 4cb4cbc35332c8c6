#include "habuffer/gl/gl_spatial_hash.h"

#include <epoxy/gl.h>

#include <bit>
#include <limits>
#include <stdexcept>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec4.hpp>

#include "compute_grid.h"
#include "gl_state_guard.h"
#include "gpu_timer.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/gl_technique.h"
#include "habuffer/gl/glsl_sources.h"
#include "habuffer/gl/technique_registry.h"
#include "lookup_points.h"
#include "spatial_glsl.h"

namespace habuffer::gl {
namespace {

constexpr unsigned kResumeLimitPasses = 4096;
constexpr unsigned kLockSpinLimit = 1u << 12;

// The block HabufferSpatial of spatial_block.glsl, std140.
struct SpatialBlock {
  std::uint32_t table_size[2];
  std::uint32_t age_bits, quotient_x, max_age_cells_x, block, iter_limit, complement;
  std::uint32_t domain[3];
  std::uint32_t interleave_shift, slices_per_row;
  std::uint32_t filter_blocks_x, filter_base, filter_shift_y;
};
static_assert(sizeof(SpatialBlock) == 64, "HabufferSpatial's std140 layout (spatial_block.glsl)");

SpatialBlock block_of(const spatial::SpatialHash& table) {
  const spatial::SpatialKernelParams& k = table.kernel_params();
  const spatial::FoldedDomain& f = table.domain();
  SpatialBlock b{};
  b.table_size[0] = k.table.x;
  b.table_size[1] = k.table.y;
  b.age_bits = k.age_bits;
  b.quotient_x = k.quotient_x;
  b.max_age_cells_x = k.cells_x;
  b.block = k.block;
  b.iter_limit = k.iter_limit;
  b.complement = table.config().rule == spatial::DuplicateRule::Min ? 1u : 0u;
  b.domain[0] = f.domain().x;
  b.domain[1] = f.domain().y;
  b.domain[2] = f.domain().z;
  b.interleave_shift = static_cast<std::uint32_t>(std::countr_zero(f.interleave()));
  b.slices_per_row = f.slices_per_row();
  b.filter_blocks_x = k.filter_blocks_x;
  b.filter_base = static_cast<std::uint32_t>(table.max_age().size());
  b.filter_shift_y = k.filter_shift_y;
  return b;
}

// The shader of `entry` on the HA-buffer's shared parts: the mode's
// extensions and 64-bit atomics prelude (the modules' own, module_extensions
// and mode_prelude), the shared probe, the spatial hash's GLSL and its keys'
// (the parameter block at GlBindings' uniform point).
std::string source(const GlBindings& bindings, AtomicMode mode, const char* entry) {
  return "#version 450\n" + module_extensions(mode) + bindings.glsl_defines() +
         "#define ha_word uint64_t\n#define ha_index uint\n#define HABUFFER_RECORDS_BINDING HABUFFER_BINDING_TABLE\n"
         "#define HABUFFER_SPATIAL_BINDING_PARAMS HABUFFER_BINDING_PARAMS\n"
         "uniform uint habuffer_lock_spin_limit;\n" +
         join_parts({kHaConstants, mode_prelude(mode), kShConstants, kShBlock, kShEnv, kHaProbe, kShSpatial, kShKeys,
                     entry});
}

// One refusal of the rules a concurrent GPU insert cannot order (GlSpatialHash::insert, gl_insert).
void check_rule(spatial::DuplicateRule rule) {
  if (rule == spatial::DuplicateRule::First || rule == spatial::DuplicateRule::Last)
    throw std::invalid_argument("spatial hash on the GPU: rule " + to_string(rule) +
                                " orders a batch, which concurrent GPU calls do not: use max or min, or the CPU table");
}

std::string key_text(glm::uvec3 k) {
  return "(" + std::to_string(k.x) + ", " + std::to_string(k.y) + ", " + std::to_string(k.z) + ")";
}

// Every key in the domain, checked before any GL work (SpatialHash's wording).
void check_keys(const spatial::FoldedDomain& fold, std::span<const glm::uvec3> keys) {
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (!fold.contains(keys[i]))
      throw std::invalid_argument("spatial hash: key " + std::to_string(i) + " " + key_text(keys[i]) +
                                  " is outside the domain " + fold.domain().str());
}

void check_count(std::size_t keys) {
  if (keys > std::numeric_limits<std::uint32_t>::max())
    throw std::invalid_argument("spatial hash: a batch of " + std::to_string(keys) +
                                " keys; insert or find at most 2^32 - 1 at once");
}

// A host's buffer holding at least `bytes`.
void check_host_buffer(unsigned buffer, std::uint64_t bytes, const char* what) {
  if (glIsBuffer(buffer) == GL_FALSE)
    throw std::invalid_argument(std::string("spatial hash on the GPU: the ") + what + " buffer " +
                                std::to_string(buffer) + " is not a buffer object");
  GLint64 size = 0;
  glGetNamedBufferParameteri64v(buffer, GL_BUFFER_SIZE, &size);
  if (static_cast<std::uint64_t>(size) < bytes)
    throw std::invalid_argument(std::string("spatial hash on the GPU: the ") + what + " buffer " +
                                std::to_string(buffer) + " holds " + std::to_string(size) + " bytes, " +
                                std::to_string(bytes) + " needed");
}

// Keys as the passes read them: (x, y, z, 0), 16 bytes each.
std::vector<glm::uvec4> padded(std::span<const glm::uvec3> keys) {
  std::vector<glm::uvec4> out(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) out[i] = {keys[i], 0u};
  return out;
}

void check_size(std::uint64_t bytes, const char* what) {
  if (bytes > max_storage_bytes())
    throw GlError(std::string("spatial hash on the GPU: the ") + what + " takes " + std::to_string(bytes) +
                  " bytes, beyond the driver's " + std::to_string(max_storage_bytes()) + " per shader-storage buffer");
}

// The buffers an insert of `keys` keys allocates (each carry of a call cut short: 32 bytes), within the driver's limit.
void check_batch(std::uint64_t keys) { check_size(keys * 32, "carries of calls cut short"); }

AtomicMode mode_for_context(const GlInfo& info) {
  const std::optional<AtomicMode> mode = chosen_atomic_mode(info, Layout::L64);
  if (!mode) throw GlError("spatial hash on the GPU: this context has no 64-bit integers in shaders");
  return *mode;
}

}  // namespace

void GlSpatialBindings::validate(const GlBindings& view) const {
  const LookupPoint storage[] = {{"table", table}, {"max_age", max_age}, {"offsets", offsets}};
  validate_lookup_points("GlSpatialBindings", storage, {"params", params}, view);
}

std::string GlSpatialBindings::glsl_defines(bool overridable) const {
  const LookupPoint all[] = {{"table", table}, {"max_age", max_age}, {"offsets", offsets}, {"params", params}};
  return lookup_defines("HABUFFER_SPATIAL_BINDING_", all, overridable);
}

std::string spatial_lookup_part(const GlSpatialBindings& bindings, bool overridable) {
  // The constants (the miss filter's block) and the block, then the environment.
  std::string s = bindings.glsl_defines(overridable) + kShConstants + "\n" + kShBlock + "\n" + kShLookupEnv + "\n";
  // The shared probe, record and key sources under sh_ (a technique module's ha_ instance may sit beside them).
  for (const char* shared : {kHaProbe, kShSpatial, kShKeys}) s += replace_identifiers(shared, "ha_", "sh_", false) + "\n";
  return s + kShLookup;
}

GlSpatialHash::GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings)
    : GlSpatialHash(table, bindings, query_gl_info()) {}  // query_gl_info checks for a context first

GlSpatialHash::GlSpatialHash(const spatial::SpatialHash& table, const GlBindings& bindings, const GlInfo& info)
    : context_("GlSpatialHash"),
      bindings_(bindings),
      config_(table.config()),
      fold_(table.domain()),
      mode_(mode_for_context(info)),
      // GPU timestamps time the shaders, but not on Mesa's software
      // rasterizers (submission times: microseconds for a pass of seconds).
      timed_(!info.software_rasterizer),
      records_(ShaderProgram::compute(source(bindings_, mode_, kShRecordsCompute), "spatial hash records compute shader")),
      insert_(ShaderProgram::compute(source(bindings_, mode_, kShInsertCompute), "spatial hash insert compute shader")),
      find_(ShaderProgram::compute(source(bindings_, mode_, kShFindCompute), "spatial hash find compute shader")) {
  slot_count_ = table.table().size();
  cell_count_ = table.max_age().size();
  filter_count_ = table.filter().size();
  if (slot_count_ > 0xFFFFFFFFull) throw GlError("spatial hash on the GPU: more than 2^32 slots");
  check_size(slot_count_ * 8, "table");
  check_size((cell_count_ + filter_count_) * 4, "max-age cells and miss filter");
  table_ = GlStorage(slot_count_ * 8, table.table().data());
  // One buffer: the max-age cells, then the miss filter's words (filter_base).
  std::vector<std::uint32_t> cells(table.max_age().begin(), table.max_age().end());
  cells.insert(cells.end(), table.filter().begin(), table.filter().end());
  max_age_ = GlStorage(cells.size() * 4, cells.data());
  const std::span<const glm::uvec2> o = table.offsets().values();
  offsets_ = GlStorage(o.size() * sizeof(glm::uvec2), o.data());
  const SpatialBlock block = block_of(table);
  params_ = GlStorage(sizeof block, &block);
  if (mode_ != AtomicMode::Native64) {
    locks_ = GlStorage(((slot_count_ >> 3) + 1) * 4);
    locks_.zero();
  }
}

spatial::InsertReport GlSpatialHash::insert(std::span<const glm::uvec3> keys, std::span<const std::uint32_t> stored,
                                            std::vector<Dropped>& dropped) {
  context_.check("GlSpatialHash::insert");
  check_rule(config_.rule);
  if (!stored.empty() && stored.size() != keys.size())
    throw std::invalid_argument("spatial hash: " + std::to_string(keys.size()) + " keys but " +
                                std::to_string(stored.size()) + " stored values");
  check_count(keys.size());
  check_keys(fold_, keys);
  check_batch(keys.size());
  resume_passes_ = 0;
  if (keys.empty()) return {};
  const std::vector<glm::uvec4> k = padded(keys);
  const GlStorage key_buffer(k.size() * sizeof(glm::uvec4), k.data());
  const GlStorage value_buffer = stored.empty() ? GlStorage() : GlStorage(stored.size_bytes(), stored.data());
  return insert_buffers(key_buffer.id(), value_buffer.id(), static_cast<std::uint32_t>(keys.size()), dropped);
}

spatial::InsertReport GlSpatialHash::insert(unsigned keys, unsigned stored, std::uint32_t count,
                                            std::vector<Dropped>& dropped) {
  context_.check("GlSpatialHash::insert");
  check_rule(config_.rule);
  check_batch(count);
  resume_passes_ = 0;
  if (count == 0) return {};
  check_host_buffer(keys, std::uint64_t{count} * 16, "keys");
  if (stored != 0) check_host_buffer(stored, std::uint64_t{count} * 4, "stored values");
  return insert_buffers(keys, stored, count, dropped);
}

spatial::InsertReport GlSpatialHash::insert_buffers(unsigned keys, unsigned stored, std::uint32_t count,
                                                    std::vector<Dropped>& dropped) {
  const GlStateGuard guard(bindings_);
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);  // the host's writes to its buffers
  const GlStorage records = make_records(keys, stored, count);
  return insert_records(records, count, dropped);
}

GlStorage GlSpatialHash::make_records(unsigned keys, unsigned stored, std::uint32_t count) const {
  GlStorage records(std::uint64_t{count} * sizeof(glm::uvec4));
  const std::uint32_t start[2] = {0u, 0xFFFFFFFFu};  // keys outside the domain, the first one's index
  const GlStorage counters(sizeof start, start);
  bind_table();
  bind_at(GL_SHADER_STORAGE_BUFFER, bindings_.stream, keys);
  if (stored != 0) bind_at(GL_SHADER_STORAGE_BUFFER, bindings_.deferred, stored);
  records.bind_storage(bindings_.capture);
  counters.bind_storage(bindings_.counters);
  glUseProgram(records_.id());
  records_.set("sh_count", count);
  records_.set("sh_has_values", stored != 0 ? 1u : 0u);
  const GpuTimer timer;
  timer.begin();
  dispatch_grid(count, 64);
  timer.end();
  gpu_ms_ = timed_ ? timer.milliseconds() : 0.0;  // the insert's first pass
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::vector<std::uint32_t> c = counters.read_words(2);
  if (c[0] != 0) {
    glm::uvec4 key{0u};
    glGetNamedBufferSubData(keys, static_cast<GLintptr>(std::uint64_t{c[1]} * 16), 16, &key);
    throw std::invalid_argument("spatial hash on the GPU: " + std::to_string(c[0]) + " of " + std::to_string(count) +
                                " keys are outside the domain " + config_.domain.str() + ", the first key " +
                                std::to_string(c[1]) + " " + key_text(glm::uvec3(key)) + "; nothing inserted");
  }
  return records;
}

spatial::InsertReport GlSpatialHash::insert_records(const GlStorage& input, std::uint32_t count,
                                                    std::vector<Dropped>& dropped) {
  spatial::InsertReport report;
  report.calls = count;
  GlStorage carries[2] = {GlStorage(std::uint64_t{count} * 32), GlStorage(std::uint64_t{count} * 32)};
  const GlStorage drops(std::uint64_t{count} * 16);
  const GlStorage counters(16 * 4);
  counters.zero();
  bind_table();
  drops.bind_storage(bindings_.capture);
  counters.bind_storage(bindings_.counters);
  glUseProgram(insert_.id());
  insert_.set("habuffer_lock_spin_limit", kLockSpinLimit);
  std::uint64_t pending = count;
  for (unsigned pass = 0;; ++pass) {
    (pass == 0 ? input : carries[pass % 2]).bind_storage(bindings_.stream);  // records, or the cut calls to resume
    carries[(pass + 1) % 2].bind_storage(bindings_.deferred);              // the calls this pass cuts short
    insert_.set("sh_count", static_cast<unsigned>(pending));
    insert_.set("sh_resume", pass == 0 ? 0u : 1u);
    const GpuTimer timer;
    timer.begin();
    dispatch_grid(pending, 64);
    timer.end();
    gpu_ms_ = timed_ ? gpu_ms_ + timer.milliseconds() : 0.0;
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
    std::vector<std::uint32_t> c = counters.read_words(16);
    pending = c[8];
    if (pending == 0) break;
    if (pass + 1 >= kResumeLimitPasses)
      throw GlError("spatial hash on the GPU: " + std::to_string(pending) + " calls still cut short after " +
                    std::to_string(kResumeLimitPasses) + " passes");
    ++resume_passes_;
    const std::uint32_t zero = 0;
    glNamedBufferSubData(counters.id(), 8 * 4, 4, &zero);
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
  context_.check("GlSpatialHash::find");
  if (stored.size() != keys.size() || found.size() != keys.size())
    throw std::invalid_argument("spatial hash: find of " + std::to_string(keys.size()) + " keys into " +
                                std::to_string(stored.size()) + " stored values and " + std::to_string(found.size()) +
                                " flags");
  check_count(keys.size());
  check_keys(fold_, keys);
  if (keys.empty()) return 0;
  check_size(keys.size() * sizeof(glm::uvec4), "queries");
  const GlStateGuard guard(bindings_);
  const std::vector<glm::uvec4> k = padded(keys);
  const GlStorage queries(k.size() * sizeof(glm::uvec4), k.data());
  const GlStorage answers(k.size() * sizeof(glm::uvec2));
  bind_table();
  queries.bind_storage(bindings_.stream);
  answers.bind_storage(bindings_.capture);
  glUseProgram(find_.id());
  find_.set("sh_count", static_cast<unsigned>(k.size()));
  const GpuTimer timer;
  timer.begin();
  dispatch_grid(k.size(), 64);
  timer.end();
  gpu_ms_ = timed_ ? timer.milliseconds() : 0.0;
  glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
  const std::vector<glm::uvec2> a = answers.read<glm::uvec2>(k.size());
  std::uint64_t hits = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    found[i] = a[i].x != 0u ? 1u : 0u;
    stored[i] = a[i].y;
    hits += a[i].x;
  }
  return hits;
}

void GlSpatialHash::bind_for_lookup(const GlSpatialBindings& bindings) const {
  context_.check("GlSpatialHash::bind_for_lookup");
  bindings.validate(bindings_);
  bind_at(GL_SHADER_STORAGE_BUFFER, bindings.table, table_.id());
  bind_at(GL_SHADER_STORAGE_BUFFER, bindings.max_age, max_age_.id());
  bind_at(GL_SHADER_STORAGE_BUFFER, bindings.offsets, offsets_.id());
  bind_at(GL_UNIFORM_BUFFER, bindings.params, params_.id());
}

void GlSpatialHash::bind_table() const {
  bind_at(GL_UNIFORM_BUFFER, bindings_.params, params_.id());
  table_.bind_storage(bindings_.table);
  max_age_.bind_storage(bindings_.max_age);
  offsets_.bind_storage(bindings_.offsets);
  locks_.bind_storage(bindings_.locks);
}

void GlSpatialHash::clear() {
  context_.check("GlSpatialHash::clear");
  table_.zero();
  max_age_.zero();
}

std::vector<std::uint64_t> GlSpatialHash::slots() const {
  context_.check("GlSpatialHash::slots");
  return table_.read<std::uint64_t>(slot_count_);
}
std::vector<std::uint32_t> GlSpatialHash::max_age() const {
  context_.check("GlSpatialHash::max_age");
  return max_age_.read<std::uint32_t>(cell_count_);
}
std::vector<std::uint32_t> GlSpatialHash::filter() const {
  context_.check("GlSpatialHash::filter");
  std::vector<std::uint32_t> words = max_age_.read<std::uint32_t>(cell_count_ + filter_count_);
  words.erase(words.begin(), words.begin() + static_cast<std::ptrdiff_t>(cell_count_));
  return words;
}

spatial::InsertReport gl_insert(spatial::SpatialHash& table, std::span<const glm::uvec3> keys,
                                std::span<const std::uint32_t> values) {
  const spatial::SpatialHashConfig c = table.config();
  check_rule(c.rule);
  if (!values.empty() && values.size() != keys.size())
    throw std::invalid_argument("spatial hash: " + std::to_string(keys.size()) + " keys but " +
                                std::to_string(values.size()) + " values");
  check_keys(table.domain(), keys);
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
