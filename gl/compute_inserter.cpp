#include "habuffer/gl/compute_inserter.h"

#include <epoxy/gl.h>

#include <algorithm>
#include <array>

#include "habuffer/gl/debug_output.h"
#include "habuffer/gl/gl_error.h"
#include "habuffer/gl/glsl_sources.h"

namespace habuffer::gl {
namespace {

constexpr GLuint kBindings = 6;  // table, max age, offsets, fragments, counters, locks

// Saves the program and shader-storage bindings we use; restores them on exit.
class StateGuard {
 public:
  StateGuard() {
    glGetIntegerv(GL_CURRENT_PROGRAM, &program_);
    for (GLuint i = 0; i < kBindings; ++i) {
      glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, i, &buffers_[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_START, i, &starts_[i]);
      glGetInteger64i_v(GL_SHADER_STORAGE_BUFFER_SIZE, i, &sizes_[i]);
    }
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &generic_);
  }
  ~StateGuard() {
    glUseProgram(static_cast<GLuint>(program_));
    for (GLuint i = 0; i < kBindings; ++i) {
      if (sizes_[i] > 0)
        glBindBufferRange(GL_SHADER_STORAGE_BUFFER, i, static_cast<GLuint>(buffers_[i]), starts_[i], sizes_[i]);
      else
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, static_cast<GLuint>(buffers_[i]));
    }
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, static_cast<GLuint>(generic_));
  }
  StateGuard(const StateGuard&) = delete;
  StateGuard& operator=(const StateGuard&) = delete;

 private:
  GLint program_ = 0, generic_ = 0;
  std::array<GLint, kBindings> buffers_{};
  std::array<GLint64, kBindings> starts_{}, sizes_{};
};

GLuint make_buffer(GLsizeiptr bytes, const void* data) {
  GLuint b = 0;
  glCreateBuffers(1, &b);
  glNamedBufferData(b, std::max<GLsizeiptr>(bytes, 4), data, GL_DYNAMIC_DRAW);
  return b;
}

void zero(GLuint buffer) {
  const GLuint z = 0;
  glClearNamedBufferData(buffer, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, &z);
}

std::vector<std::uint32_t> read(GLuint buffer, std::size_t words) {
  std::vector<std::uint32_t> out(words);
  glGetNamedBufferSubData(buffer, 0, static_cast<GLsizeiptr>(words * 4), out.data());
  return out;
}

}  // namespace

ComputeInserter::ComputeInserter(const BufferConfig& config, const OffsetSequence& offsets, AtomicMode mode)
    : config_(config), program_(ShaderProgram::compute(insert_stream_compute(mode), "insert compute shader")) {
  config_.validate();
  config_.table = config.table_or_screen();
  if (mode == AtomicMode::Native32 && config_.layout != Layout::L32)
    throw GlError("atomic mode native32 holds L32 records only");
  if (mode != AtomicMode::Native32 && config_.layout != Layout::L64)
    throw GlError("atomic mode " + to_string(mode) + " holds L64 records only");
  if (config_.table.area() > UINT32_MAX) throw GlError("the GPU path indexes at most 2^32 - 1 slots, table " + config_.table.str());
  const std::uint32_t amax = config_.record_layout().max_age();
  if (offsets.table() != config_.table || offsets.size() != amax) throw GlError("offsets do not match the table and age bits");
  cells_ = ((config_.screen.x + config_.block - 1) / config_.block) * ((config_.screen.y + config_.block - 1) / config_.block);
  word_bytes_ = config_.record_layout().word_bytes();
  table_ = make_buffer(static_cast<GLsizeiptr>(config_.table.area() * word_bytes_), nullptr);
  if (mode == AtomicMode::Emulated64) {
    locks_ = make_buffer(static_cast<GLsizeiptr>(config_.table.area() * 4), nullptr);
    zero(locks_);  // every critical section leaves its lock at 0 again
  }
  max_age_ = make_buffer(static_cast<GLsizeiptr>(cells_) * 4, nullptr);
  offsets_ = make_buffer(static_cast<GLsizeiptr>(offsets.size() * sizeof(glm::uvec2)), offsets.values().data());
  counters_ = make_buffer(8 * 4, nullptr);
  clear();
  const ShaderProgram& p = program_;
  p.set("ha_age_bits", config_.age_bits);
  p.set("ha_table_size", config_.table.x, config_.table.y);
  p.set("ha_block", config_.block);
  p.set("ha_max_age_cells_x", (config_.screen.x + config_.block - 1) / config_.block);
  p.set("ha_iter_limit", config_.iter_limit);
  p.set("ha_cull_tau", config_.early_cull_tau);
  check_gl_errors("creating the compute inserter");
}

ComputeInserter::~ComputeInserter() {
  const GLuint buffers[] = {table_, max_age_, offsets_, fragments_, counters_, locks_};
  glDeleteBuffers(6, buffers);
}

void ComputeInserter::clear() {
  zero(table_);
  zero(max_age_);
}

Counters ComputeInserter::insert(std::span<const Fragment> fragments) {
  for (std::size_t i = 0; i < fragments.size(); ++i)
    if (fragments[i].x >= config_.screen.x || fragments[i].y >= config_.screen.y)
      throw GlError("fragment " + std::to_string(i) + " lies outside screen " + config_.screen.str());
  const StateGuard guard;
  if (fragments_ != 0) glDeleteBuffers(1, &fragments_);
  fragments_ = make_buffer(static_cast<GLsizeiptr>(fragments.size_bytes()), fragments.data());
  zero(counters_);
  glUseProgram(program_.id());
  const GLuint buffers[] = {table_, max_age_, offsets_, fragments_, counters_, locks_};
  for (GLuint i = 0; i < kBindings; ++i)
    if (buffers[i] != 0) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, buffers[i]);
  program_.set("ha_fragment_count", static_cast<unsigned>(fragments.size()));
  const auto groups = static_cast<GLuint>(std::clamp<std::size_t>((fragments.size() + 63) / 64, 1, 65535));
  glDispatchCompute(groups, 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
  const auto c = read(counters_, 8);
  check_gl_errors("compute insertion");
  Counters counters;
  const std::uint64_t tally[HA_OUTCOME_COUNT] = {c[0], c[1], c[2], c[3], c[4], c[5]};
  counters.add_tally(tally);
  if (counters.fragments != fragments.size()) throw GlError("GPU insert lost track of fragments");
  return counters;
}

std::vector<std::uint64_t> ComputeInserter::read_table() const {
  const std::uint64_t slots = config_.table.area();
  std::vector<std::uint64_t> out(slots);
  if (word_bytes_ == 8) {
    glGetNamedBufferSubData(table_, 0, static_cast<GLsizeiptr>(slots * 8), out.data());
  } else {
    const auto words = read(table_, slots);
    std::copy(words.begin(), words.end(), out.begin());
  }
  return out;
}
std::vector<std::uint32_t> ComputeInserter::read_max_age() const { return read(max_age_, cells_); }

}  // namespace habuffer::gl
