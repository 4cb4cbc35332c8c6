// The spatial hash on the GPU (habuffer/gl/gl_spatial_hash.h): the table the
// compute shaders build is the CPU's bit for bit, lookups answer as the
// CPU's do, calls cut short are resumed, failed calls grow the table, and
// the host's GL bindings come back as they were; misuse is refused before
// any GL work (rules, domain, spans) and host shaders look the table up as
// the CPU does (habuffer_spatial_find).
#include <gtest/gtest.h>

#include <epoxy/gl.h>

#include <map>
#include <random>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include <glm/vec4.hpp>

#include "gl_test_support.h"
#include "habuffer/gl/host_glsl_files.h"
#include "habuffer/gl.h"  // the one include has the spatial hash on the GPU too
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

// The miss filter (issue 36): the GPU's atomic ors leave the CPU's words;
// its lookups, with the filter and without one, answer as the CPU's.
TEST(GlSpatialHash, TheGpusMissFilterIsTheCpusWordForWordAndLookupsAnswerAlikeWithAndWithoutIt) {
  gl_context();
  for (const bool three_d : {false, true}) {
    SCOPED_TRACE(three_d ? "3D" : "2D");
    KeySetOptions o;
    o.set = three_d ? KeySet::VoxelShell : KeySet::SparseImage;
    o.domain = three_d ? Domain{40, 40, 40} : Domain{160, 120, 1};
    const std::vector<glm::uvec3> keys = make_keys(o);
    const std::vector<glm::uvec3> absent = absent_keys(keys, o.domain, 3000, 10);
    const std::vector<std::uint32_t> values = values_for(keys.size(), 5);
    SpatialHash cpu(config_of(o.domain, DuplicateRule::Max));
    cpu.reserve(keys.size(), 0.95);
    gl::GlSpatialHash gpu(cpu);
    std::vector<gl::GlSpatialHash::Dropped> dropped;
    gpu.insert(keys, values, dropped);
    ASSERT_TRUE(dropped.empty());
    cpu.insert(keys, values);
    const std::vector<std::uint64_t> slots = gpu.slots();
    ASSERT_TRUE(std::equal(slots.begin(), slots.end(), cpu.table().begin(), cpu.table().end()));
    const std::vector<std::uint32_t> words = gpu.filter();
    ASSERT_FALSE(words.empty());
    EXPECT_TRUE(std::equal(words.begin(), words.end(), cpu.filter().begin(), cpu.filter().end()));
    std::vector<glm::uvec3> queries = keys;
    queries.insert(queries.end(), absent.begin(), absent.end());
    std::vector<std::uint32_t> cv(queries.size());
    std::vector<std::uint8_t> cf(queries.size());
    cpu.find(queries, cv, cf);
    for (const std::uint32_t bits : {8u, 0u}) {
      cpu.set_miss_filter(bits);
      const gl::GlSpatialHash uploaded(cpu);
      EXPECT_EQ(uploaded.filter().empty(), bits == 0u);
      std::vector<std::uint32_t> gv(queries.size());
      std::vector<std::uint8_t> gf(queries.size());
      EXPECT_EQ(uploaded.find(queries, gv, gf), keys.size());
      EXPECT_EQ(gv, cv);
      EXPECT_EQ(gf, cf);
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

// Runs `call`, which must throw std::invalid_argument whose one-line
// message holds every piece of `pieces`.
template <class F>
void expect_refused(F call, std::initializer_list<const char*> pieces) {
  try {
    call();
    ADD_FAILURE() << "not refused";
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    for (const char* p : pieces) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' not in: " << m;
  }
}

// A host's own storage buffer holding `data`.
template <class T>
GLuint host_buffer(const std::vector<T>& data) {
  GLuint b = 0;
  glCreateBuffers(1, &b);
  glNamedBufferStorage(b, static_cast<GLsizeiptr>(std::max<std::size_t>(data.size() * sizeof(T), 4)), data.data(), 0);
  return b;
}

std::vector<glm::uvec4> as_host_keys(const std::vector<glm::uvec3>& keys, std::uint32_t w) {
  std::vector<glm::uvec4> out;
  for (const glm::uvec3& k : keys) out.push_back({k, w});  // the fourth word is the host's: ignored
  return out;
}

// Distinct random keys of `d` with random values, inserted into `table` on the CPU.
std::vector<glm::uvec3> random_keys(Domain d, std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::set<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> seen;
  std::vector<glm::uvec3> keys;
  while (keys.size() < n) {
    const glm::uvec3 k(rng() % d.x, rng() % d.y, rng() % d.z);
    if (seen.insert({k.x, k.y, k.z}).second) keys.push_back(k);
  }
  return keys;
}

TEST(GlSpatialHash, InsertRefusesTheRulesFirstAndLastByNameWhileLookupsOfSuchTablesWork) {
  gl_context();
  for (const DuplicateRule rule : {DuplicateRule::Last, DuplicateRule::First}) {
    SpatialHashConfig c = config_of({64, 64, 1}, rule);
    SpatialHash cpu(c, 100);
    const std::vector<glm::uvec3> keys = {{1, 2, 0}, {3, 4, 0}, {1, 2, 0}};
    const std::vector<std::uint32_t> values = {5, 6, 7};
    cpu.insert(keys, values);
    gl::GlSpatialHash gpu(cpu);  // any table uploads: lookups do not depend on the rule
    std::vector<gl::GlSpatialHash::Dropped> dropped;
    const std::string name = "rule " + to_string(rule);
    expect_refused([&] { (void)gpu.insert(keys, values, dropped); }, {name.c_str(), "use max or min"});
    const GLuint k = host_buffer(as_host_keys(keys, 0));
    expect_refused([&] { (void)gpu.insert(k, 0, 3, dropped); }, {name.c_str(), "use max or min"});
    glDeleteBuffers(1, &k);
    SpatialHash copy = cpu;
    expect_refused([&] { (void)gl::gl_insert(copy, keys, values); }, {name.c_str(), "use max or min"});
    EXPECT_TRUE(std::equal(cpu.table().begin(), cpu.table().end(), gpu.slots().begin()));  // nothing changed
    std::vector<std::uint32_t> stored(2);
    std::vector<std::uint8_t> found(2);
    EXPECT_EQ(gpu.find(std::vector<glm::uvec3>{{1, 2, 0}, {3, 3, 0}}, stored, found), 1u);
    EXPECT_EQ(stored[0], *cpu.find({1, 2, 0}));
  }
}

TEST(GlSpatialHash, KeysOutsideTheDomainAreRefusedOnInsertAndFindNamingTheFirstKeyAndTheDomain) {
  gl_context();
  SpatialHash cpu(config_of({16, 128, 16}, DuplicateRule::Max), 200);
  cpu.insert(glm::uvec3{5, 6, 15}, 9);
  gl::GlSpatialHash gpu(cpu);
  const std::vector<std::uint64_t> before = gpu.slots();
  // (5, 134, 7) once aliased (5, 6, 15): its y is past the domain's 128.
  const std::vector<glm::uvec3> keys = {{1, 1, 1}, {5, 134, 7}, {16, 0, 0}};
  const std::vector<std::uint32_t> values = {1, 2, 3};
  std::vector<gl::GlSpatialHash::Dropped> dropped;
  expect_refused([&] { (void)gpu.insert(keys, values, dropped); }, {"key 1 (5, 134, 7)", "domain 16x128x16"});
  EXPECT_EQ(gpu.slots(), before);
  std::vector<std::uint32_t> stored(3);
  std::vector<std::uint8_t> found(3);
  expect_refused([&] { (void)gpu.find(keys, stored, found); }, {"key 1 (5, 134, 7)", "domain 16x128x16"});
  expect_refused([&] { (void)gpu.find(std::vector<glm::uvec3>{{0, 0, 16}}, std::span(stored).first(1),
                                      std::span(found).first(1)); },
                 {"key 0 (0, 0, 16)", "domain 16x128x16"});
}

TEST(GlSpatialHash, KeysOutsideTheDomainInAHostBufferAreCountedOnTheGpuAndRefusedWithTheTableUnchanged) {
  gl_context();
  SpatialHash cpu(config_of({16, 128, 16}, DuplicateRule::Max), 2000);
  std::vector<glm::uvec3> keys = random_keys({16, 128, 16}, 1000, 11);
  cpu.insert(std::span(keys).first(10));
  gl::GlSpatialHash gpu(cpu);
  const std::vector<std::uint64_t> before = gpu.slots();
  const std::vector<std::uint32_t> ages = gpu.max_age();
  keys[417] = {5, 134, 7};
  keys[600] = {16, 3, 3};
  keys[901] = {0, 0, 0xFFFFFFFFu};
  const GLuint k = host_buffer(as_host_keys(keys, 7));
  std::vector<gl::GlSpatialHash::Dropped> dropped;
  expect_refused([&] { (void)gpu.insert(k, 0, static_cast<std::uint32_t>(keys.size()), dropped); },
                 {"3 of 1000 keys", "first key 417 (5, 134, 7)", "domain 16x128x16", "nothing inserted"});
  glDeleteBuffers(1, &k);
  EXPECT_EQ(gpu.slots(), before);
  EXPECT_EQ(gpu.max_age(), ages);
  EXPECT_TRUE(dropped.empty());
}

TEST(GlSpatialHash, SpansAndHostBuffersOfTheWrongSizeAreRefusedBeforeAnyGlWork) {
  gl_context();
  SpatialHash cpu(config_of({64, 64, 1}, DuplicateRule::Max), 100);
  gl::GlSpatialHash gpu(cpu);
  const std::vector<glm::uvec3> keys = {{1, 2, 0}, {3, 4, 0}, {5, 6, 0}};
  std::vector<std::uint32_t> values(2), stored(2), wide(4);
  std::vector<std::uint8_t> found(3), few(2);
  std::vector<gl::GlSpatialHash::Dropped> dropped;
  expect_refused([&] { (void)gpu.insert(keys, values, dropped); }, {"3 keys but 2 stored values"});
  expect_refused([&] { (void)gpu.find(keys, stored, found); }, {"find of 3 keys into 2 stored values and 3 flags"});
  expect_refused([&] { (void)gpu.find(keys, wide, found); }, {"find of 3 keys into 4 stored values and 3 flags"});
  values.resize(3);
  expect_refused([&] { (void)gpu.find(keys, values, few); }, {"find of 3 keys into 3 stored values and 2 flags"});
  const GLuint k = host_buffer(as_host_keys(keys, 0));
  const GLuint v = host_buffer(std::vector<std::uint32_t>{1, 2});
  expect_refused([&] { (void)gpu.insert(k, v, 3, dropped); }, {"stored values buffer", "holds 8 bytes, 12 needed"});
  expect_refused([&] { (void)gpu.insert(k, 0, 4, dropped); }, {"keys buffer", "holds 48 bytes, 64 needed"});
  expect_refused([&] { (void)gpu.insert(k + v + 100, 0, 1, dropped); }, {"is not a buffer object"});
  glDeleteBuffers(1, &k);
  glDeleteBuffers(1, &v);
  EXPECT_EQ(gpu.slots(), std::vector<std::uint64_t>(cpu.table().begin(), cpu.table().end()));
}

TEST(GlSpatialHash, InsertsFromHostBuffersEqualTheSpanInsertBitForBit) {
  gl_context();
  for (const bool with_values : {true, false}) {
    SCOPED_TRACE(with_values ? "values" : "a set");
    const Domain d{40, 24, 9};  // 3D: the fold on the GPU (groups of 4 slices, a partial last group)
    std::vector<glm::uvec3> keys = random_keys(d, 3000, 5);
    std::vector<std::uint32_t> values = values_for(keys.size(), 6);
    for (std::size_t i = 0; i < 3000; i += 7) {  // repeats with other values
      keys.push_back(keys[i]);
      values.push_back(values[i] ^ 0x0F0F0F0Fu);
    }
    if (!with_values) values.clear();
    SpatialHash cpu(config_of(d, DuplicateRule::Max));
    cpu.reserve(3000, 0.9);
    gl::GlSpatialHash from_span(cpu), from_buffers(cpu);
    std::vector<gl::GlSpatialHash::Dropped> a, b;
    const InsertReport rs = from_span.insert(keys, values, a);
    const GLuint k = host_buffer(as_host_keys(keys, 0xDEADBEEFu));
    const GLuint v = with_values ? host_buffer(values) : 0;
    const InsertReport rb = from_buffers.insert(k, v, static_cast<std::uint32_t>(keys.size()), b);
    glDeleteBuffers(1, &k);
    if (v != 0) glDeleteBuffers(1, &v);
    EXPECT_EQ(from_buffers.slots(), from_span.slots());
    EXPECT_EQ(from_buffers.max_age(), from_span.max_age());
    EXPECT_EQ(rb.stored, rs.stored);
    EXPECT_EQ(rb.duplicates, rs.duplicates);
    EXPECT_EQ(rs.stored, 3000u);
    EXPECT_TRUE(a.empty() && b.empty());
    cpu.insert(keys, values);  // and both are the CPU's table
    EXPECT_TRUE(std::equal(cpu.table().begin(), cpu.table().end(), from_buffers.slots().begin()));
  }
}

// A host compute shader's lookup over the library's buffers: found, stored
// value and decoded value of each query as uvec4.
std::vector<glm::uvec4> host_lookups(const std::string& part, const std::vector<glm::uvec3>& queries) {
  const std::string source = "#version 450 core\nlayout(local_size_x = 64) in;\n"
                             "layout(std430, binding = 0) readonly buffer HostKeys { uvec4 host_keys[]; };\n"
                             "layout(std430, binding = 1) writeonly buffer HostOut { uvec4 host_out[]; };\n"
                             "uniform uint host_count;\n" +
                             part +
                             "void main() {\n"
                             "  uint i = gl_GlobalInvocationID.x;\n"
                             "  if (i >= host_count) return;\n"
                             "  uint stored = 7u, value = 7u;\n"
                             "  bool f = habuffer_spatial_find(host_keys[i].xyz, stored);\n"
                             "  bool g = habuffer_spatial_find_value(host_keys[i].xyz, value);\n"
                             "  host_out[i] = uvec4(f ? 1u : 0u, stored, g ? 1u : 0u, value);\n"
                             "}\n";
  const gl::ShaderProgram program = gl::ShaderProgram::compute(source, "host lookup");
  const GLuint in = host_buffer(as_host_keys(queries, 0));
  const GLuint out = host_buffer(std::vector<glm::uvec4>(queries.size()));
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out);
  glUseProgram(program.id());
  program.set("host_count", static_cast<unsigned>(queries.size()));
  glDispatchCompute(static_cast<GLuint>((queries.size() + 63) / 64), 1, 1);
  glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
  std::vector<glm::uvec4> result(queries.size());
  glGetNamedBufferSubData(out, 0, static_cast<GLsizeiptr>(result.size() * sizeof(glm::uvec4)), result.data());
  glUseProgram(0);
  glDeleteBuffers(1, &in);
  glDeleteBuffers(1, &out);
  return result;
}

TEST(GlSpatialHash, AHostShaderLooksTheTableUpAsTheCpuTableDoesForPresentAbsentErasedAndOutsideKeys) {
  gl_context();
  const Domain d{40, 24, 9};
  const std::vector<glm::uvec3> keys = random_keys(d, 1500, 21);
  SpatialHash cpu(config_of(d, DuplicateRule::Min));  // values stored as complements: stored and value differ
  cpu.reserve(keys.size(), 0.95);
  cpu.insert(keys, values_for(keys.size(), 22));
  for (std::size_t i = 0; i < keys.size(); i += 10) cpu.erase(keys[i]);  // tombstones
  std::vector<glm::uvec3> queries = keys;
  for (const glm::uvec3& k : random_keys(d, 2000, 23)) queries.push_back(k);  // mostly absent
  for (const glm::uvec3 k : {glm::uvec3{5, 30, 7}, glm::uvec3{40, 0, 0}, glm::uvec3{0, 0, 9}, glm::uvec3{0xFFFFFFFFu}})
    queries.push_back(k);  // outside the domain: absent
  const gl::GlSpatialHash gpu(cpu);
  gl::GlSpatialBindings moved;  // the host's own points
  moved.table = 2;
  moved.max_age = 3;
  moved.offsets = 4;
  moved.params = 5;
  std::string file;
  for (const gl::GlslFile& f : gl::host_glsl_files())
    if (f.path == "spatial_lookup.glsl") file = f.text;
  ASSERT_FALSE(file.empty());
  const std::string file_moved = moved.glsl_defines() + file;  // the installed file after the host's #defines
  GLint generic = 0;
  const GLuint host = host_buffer(std::vector<std::uint32_t>(4));
  const SpatialHashView view = cpu.view();
  std::size_t hits = 0;
  for (const auto& [part, points] : {std::pair{gl::spatial_lookup_part(), gl::GlSpatialBindings{}},
                                     std::pair{gl::spatial_lookup_part(moved), moved}, std::pair{file_moved, moved}}) {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, host);
    gpu.bind_for_lookup(points);
    glGetIntegerv(GL_SHADER_STORAGE_BUFFER_BINDING, &generic);
    EXPECT_EQ(static_cast<GLuint>(generic), host);  // indexed bindings only
    const std::vector<glm::uvec4> got = host_lookups(part, queries);
    hits = 0;
    for (std::size_t i = 0; i < queries.size(); ++i) {
      const std::optional<std::uint32_t> want = view.find(queries[i]);
      hits += want.has_value();
      const glm::uvec4 expected = want ? glm::uvec4(1u, ~*want, 1u, *want) : glm::uvec4(0u);
      ASSERT_EQ(got[i], expected) << i << " (" << queries[i].x << ", " << queries[i].y << ", " << queries[i].z << ")";
    }
  }
  EXPECT_GE(hits, cpu.size());  // every live key (the random queries may hit some again)
  EXPECT_LT(hits, queries.size());
  glDeleteBuffers(1, &host);
}

TEST(GlSpatialHash, TheLookupSitsBesideATechniqueModuleAndItsPointsAreChecked) {
  gl_context();
  SpatialHash cpu(config_of({8, 8, 1}, DuplicateRule::Max), 4);
  const gl::GlSpatialHash gpu(cpu);
  std::map<std::string, std::string> files;
  for (const gl::GlslFile& f : gl::host_glsl_files()) files[f.path] = f.text;
  const std::string fragment = "#version 450 core\n" + files.at("emulated64/extensions.glsl") +
                               files.at("emulated64/ha.frag.glsl") + files.at("spatial_lookup.glsl") +
                               "void main() { uint v = 0u;\n"
                               "  if (habuffer_spatial_find(uvec3(gl_FragCoord.xy, 0u), v)) ha_insert_here(unpackUnorm4x8(v)); }\n";
  const std::string vertex = "#version 450 core\nvoid main() { gl_Position = vec4(0.0, 0.0, 0.0, 1.0); }\n";
  EXPECT_NO_THROW((void)gl::ShaderProgram::graphics(vertex, fragment, "gather with a spatial lookup"));
  gl::GlSpatialBindings clash;
  clash.offsets = gl::GlBindings{}.stream;
  EXPECT_THROW(gpu.bind_for_lookup(clash), gl::GlError);
  clash = {};
  clash.max_age = clash.table;
  EXPECT_THROW(gpu.bind_for_lookup(clash), gl::GlError);
}

}  // namespace
}  // namespace habuffer::spatial
