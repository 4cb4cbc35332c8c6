// The spatial hash on the GPU (habuffer/gl/gl_spatial_hash.h): the table the
// compute shaders build is the CPU's bit for bit, lookups answer as the
// CPU's do, calls cut short are resumed, failed calls grow the table, and
// the host's GL bindings come back as they were.
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <random>
#include <set>
#include <tuple>
#include <vector>

#include "gl_test_support.h"
#include "habuffer/gl/gl_spatial_hash.h"
#include "habuffer/key_streams.h"

namespace habuffer::spatial {
namespace {

using test::gl_context;

std::vector<std::uint32_t> values_for(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<std::uint32_t> v(n);
  for (auto& x : v) x = static_cast<std::uint32_t>(rng());
  return v;
}

SpatialHashConfig config_of(Domain d, DuplicateRule rule) {
  SpatialHashConfig c;
  c.domain = d;
  c.rule = rule;
  c.adaptive = false;
  c.threads = 2;
  return c;
}

TEST(GlSpatialHash, TheGpusTableIsTheCpusBitForBitAtEveryLoadWithRepeatedKeys) {
  gl_context();
  for (const double load : {0.5, 0.9, 0.99}) {
    for (const bool three_d : {false, true}) {
      SCOPED_TRACE(std::to_string(load) + (three_d ? " 3D" : " 2D"));
      KeySetOptions o;
      o.set = three_d ? KeySet::VoxelShell : KeySet::SparseImage;
      o.domain = three_d ? Domain{40, 40, 40} : Domain{160, 120, 1};
      std::vector<glm::uvec3> keys = make_keys(o);
      std::vector<std::uint32_t> values = values_for(keys.size(), 3);
      const std::size_t distinct = keys.size();
      for (std::size_t i = 0; i < distinct; i += 9) {  // repeats with other values
        keys.push_back(keys[i]);
        values.push_back(values[i] ^ 0x5A5A5A5Au);
      }
      for (const DuplicateRule rule : {DuplicateRule::Max, DuplicateRule::Min}) {
        SpatialHash cpu(config_of(o.domain, rule));
        cpu.reserve(distinct, load);
        SpatialHash gpu = cpu;
        const InsertReport c = cpu.insert(keys, values);
        const InsertReport g = gl::gl_insert(gpu, keys, values);
        ASSERT_TRUE(std::equal(cpu.table().begin(), cpu.table().end(), gpu.table().begin(), gpu.table().end()));
        EXPECT_TRUE(std::equal(cpu.max_age().begin(), cpu.max_age().end(), gpu.max_age().begin(), gpu.max_age().end()));
        EXPECT_EQ(g.duplicates, c.duplicates);
        EXPECT_EQ(g.stored, c.stored);
        EXPECT_EQ(gpu.size(), distinct);
      }
    }
  }
}

TEST(GlSpatialHash, BatchedLookupsOnTheGpuAnswerAsTheCpusForHitsAndMisses) {
  gl_context();
  KeySetOptions o;
  o.domain = {200, 150, 1};
  const std::vector<glm::uvec3> keys = make_keys(o);
  const std::vector<glm::uvec3> absent = absent_keys(keys, o.domain, 3000, 9);
  SpatialHash cpu(config_of(o.domain, DuplicateRule::Max));
  cpu.reserve(keys.size(), 0.95);
  cpu.insert(keys, values_for(keys.size(), 4));
  const gl::GlSpatialHash gpu(cpu);
  std::vector<glm::uvec3> queries = keys;
  queries.insert(queries.end(), absent.begin(), absent.end());
  std::vector<std::uint32_t> gv(queries.size()), cv(queries.size());
  std::vector<std::uint8_t> gf(queries.size()), cf(queries.size());
  EXPECT_EQ(gpu.find(queries, gv, gf), keys.size());
  EXPECT_EQ(cpu.find(queries, cv, cf), keys.size());
  EXPECT_EQ(gv, cv);
  EXPECT_EQ(gf, cf);
}

TEST(GlSpatialHash, FailedCallsOnTheGpuGrowTheTableLosslesslyAndTheHostsBindingsStay) {
  gl_context();
  SpatialHashConfig c = config_of({1u << 14, 4, 1}, DuplicateRule::Max);
  c.age_bits = 4;  // AMAX 15: keys of one position fail past it
  SpatialHash table(c, 4);
  const Extent t = table.table_extent();
  std::vector<glm::uvec3> keys;
  for (std::uint32_t j = 0; j < 40; ++j) keys.push_back({2 + j * t.x, 1, 0});
  GLuint host = 0;
  glGenBuffers(1, &host);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, host);
  glBufferData(GL_SHADER_STORAGE_BUFFER, 64, nullptr, GL_STATIC_DRAW);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 17, host);
  const InsertReport r = gl::gl_insert(table, keys);
  EXPECT_GT(r.failed_age, 0u);
  EXPECT_EQ(r.lost, 0u);
  EXPECT_EQ(table.size(), keys.size());
  for (const glm::uvec3& k : keys) EXPECT_TRUE(table.contains(k));
  GLint bound = 0;
  glGetIntegeri_v(GL_SHADER_STORAGE_BUFFER_BINDING, 17, &bound);
  EXPECT_EQ(static_cast<GLuint>(bound), host);
  glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &bound);
  EXPECT_EQ(static_cast<GLuint>(bound), host);
  glDeleteBuffers(1, &host);
  SpatialHashConfig last = c;
  last.rule = DuplicateRule::Last;
  SpatialHash ordered(last, 4);
  EXPECT_THROW((void)gl::gl_insert(ordered, keys), std::invalid_argument);
  EXPECT_THROW((void)gl::gl_insert(table, std::vector<glm::uvec3>{{1u << 14, 0, 0}}), std::invalid_argument);
}

}  // namespace
}  // namespace habuffer::spatial
