// SPEC 10 interchange files: reading errors name file, line and field.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <vector>

#include "habuffer/fenced_call.h"
#include "habuffer/interchange.h"
#include "habuffer/json_writer.h"
#include "habuffer/printable.h"
#include "test_support.h"

namespace habuffer {
namespace {

class Files : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) {
    const auto path = (dir_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  std::string read(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  void expect_error(const std::string& text, const std::string& needle, Extent screen = {4, 4}) {
    const auto path = write("bad.csv", text);
    try {
      read_fragments(path, screen);
      FAIL() << "no error for: " << text;
    } catch (const DataError& e) {
      EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("habuffer_io_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::filesystem::path dir_;
};

TEST_F(Files, FragmentsReadDecimalAndHexColoursNanAndCrLf) {
  const auto path = write("f.csv", "x,y,depth,rgba\r\n0,1,0.5,0xFF00FF80\r\n\r\n3, 3 ,nan,4294967295\n1,2,1e-50,7\n");
  const auto f = read_fragments(path, {4, 4});
  ASSERT_EQ(f.size(), 3u);
  EXPECT_EQ(f[0], (Fragment{0, 1, 0.5f, 0xFF00FF80u}));
  EXPECT_TRUE(std::isnan(f[1].depth));
  EXPECT_EQ(f[1].rgba, 0xFFFFFFFFu);
  EXPECT_EQ(f[2].depth, 0.0f) << "underflow rounds to zero, a valid depth";
}

TEST_F(Files, FragmentErrorsNameLineAndField) {
  expect_error("x,y,z,rgba\n", "header is 'x,y,z,rgba', expected 'x,y,depth,rgba'");
  expect_error("", "empty file");
  expect_error("x,y,depth,rgba\n0,0,0.5,1\n1,1,abc,2\n", ":3: field depth: 'abc' is not a number");
  expect_error("x,y,depth,rgba\n0,0,0.5\n", ":2: 3 fields, expected 4");
  expect_error("x,y,depth,rgba\n4,0,0.5,1\n", ":2: field x: 4 outside screen 4x4");
  expect_error("x,y,depth,rgba\n0,9,0.5,1\n", ":2: field y: 9 outside screen 4x4");
  expect_error("x,y,depth,rgba\n0,0,0.5,4294967296\n", "field rgba: '4294967296' does not fit in 32 bits");
  expect_error("x,y,depth,rgba\n0,0,0.5,0x1FFFFFFFF\n", "field rgba: '0x1FFFFFFFF' does not fit in 32 bits");
  expect_error("x,y,depth,rgba\n-1,0,0.5,1\n", "field x: '-1' is not an unsigned integer");
  expect_error("x,y,depth,rgba\n0,0,0.5,0xZZ\n", "field rgba: '0xZZ' is not a hexadecimal integer");
}

TEST_F(Files, MissingFileIsADataErrorNamingIt) {
  EXPECT_THROW(read_fragments((dir_ / "nope.csv").string(), {1, 1}), DataError);
}

TEST_F(Files, FragmentsRoundTripThroughWriteAndRead) {
  const auto f = test::stream({50, 40}, StreamKind::Coherent, 500, 3);
  const auto path = (dir_ / "rt.csv").string();
  write_fragments(path, f);
  EXPECT_EQ(read_fragments(path, {50, 40}), f);
}

TEST_F(Files, OffsetsFileErrorsNameTheFileAndRow) {
  const auto path = write("o.csv", "ox,oy\n0,0\n1,0\n1,0\n");
  try {
    read_offsets(path, {4, 4}, 3);
    FAIL();
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find(path + ": offsets row 3 (age 3): duplicate offset (1,0)"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(read_offsets(path, {4, 4}, 15), DataError);  // 3 rows for 15 ages
}

TEST_F(Files, DumpsHaveTheirHeadersAndFormats) {
  BufferConfig c = test::config({2, 2}, {2, 2}, Layout::L64, 8, 1);
  std::vector<glm::uvec2> rows;
  for (std::uint32_t i = 0; i < 4; ++i) rows.emplace_back(i % 2, i / 2);
  HaBuffer b(c, OffsetSequence::from_list(c.table, 255, rows));
  b.insert(std::vector<Fragment>{{1, 0, 0.5f, 0x10203040u}});
  write_table((dir_ / "t.csv").string(), b);
  write_max_age((dir_ / "m.csv").string(), b);
  write_lists((dir_ / "l.csv").string(), b);
  const std::uint64_t r = b.record_layout().pack(1, b.record_layout().depth_code(0.5f), 0x10203040u);
  char hex[32];
  std::snprintf(hex, sizeof hex, "0x%016llx", static_cast<unsigned long long>(r));
  EXPECT_EQ(read((dir_ / "t.csv").string()), "slot,record\n1," + std::string(hex) + "\n");
  EXPECT_EQ(read((dir_ / "m.csv").string()), "cx,cy,max_age\n0,0,0\n1,0,1\n0,1,0\n1,1,0\n");
  EXPECT_EQ(read((dir_ / "l.csv").string()),
            "x,y,rank,code,rgba\n1,0,0," + std::to_string(b.record_layout().depth_code(0.5f)) + ",270544960\n");
}

TEST(Json, WritesNestedValuesWithCommasAndEscapes) {
  JsonWriter j;
  j.begin_object().field("a", std::uint64_t{1}).field("s", "q\"\\\n").key("v").begin_array();
  j.value(1.5).value(std::nan("")).end_array().field("b", true).end_object();
  EXPECT_EQ(j.str(), R"({"a":1,"s":"q\"\\\u000a","v":[1.5,null],"b":true})");
}

}  // namespace
}  // namespace habuffer

namespace habuffer {
namespace {

// habuffer/fenced_call.h: what a third-party reader does in its child comes
// back as its result or as one DataError, never as the end of this process.
TEST(FencedCall, AResultComesBackWholeAndAnExceptionAsItsMessage) {
  const std::string big(3u << 20, 'x');  // more than a pipe's buffer
  EXPECT_EQ(fenced_call("r", [&] { return big; }), big);
  EXPECT_EQ(fenced_call("r", [] { return std::string(); }), "");
  try {
    (void)fenced_call("r", []() -> std::string { throw DataError("f.vdb: bad header"); });
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_STREQ(e.what(), "f.vdb: bad header");
  }
}

// Under AddressSanitizer or ThreadSanitizer a too-large operator new is
// reported by the sanitizer's allocator, which ends the child (ASan: abort,
// SIGABRT; TSan: exit 66) before any limit can make it throw bad_alloc: the
// child is still one DataError naming the reader, but a crash or an exit
// rather than the limit. (Faults need no such case: the child resets their
// handlers, the sanitizers' too.)
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
constexpr bool kSanitizerOwnsAllocation = true;
#else
constexpr bool kSanitizerOwnsAllocation = false;
#endif

TEST(FencedCall, AnAbortOrASegfaultInTheChildIsOneDataErrorNamingTheReaderAndTheSignal) {
  for (const int sig : {SIGABRT, SIGSEGV}) {
    try {
      (void)fenced_call("f.vdb: OpenVDB's reader", [sig]() -> std::string {
        std::fputs("malloc(): invalid size (unsorted)\n", stderr);  // not ours to show
        std::raise(sig);
        return "unreachable";
      });
      FAIL() << "no error";
    } catch (const DataError& e) {
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("f.vdb: OpenVDB's reader crashed on it (SIG", 0), 0u) << what;
      EXPECT_NE(what.find(sig == SIGABRT ? "SIGABRT" : "SIGSEGV"), std::string::npos) << what;
    }
  }
}

TEST(FencedCall, MemoryAndCpuBeyondTheLimitsStopTheChildNotTheMachine) {
  FenceLimits limits;
  limits.memory_bytes = 64u << 20;
  try {
    (void)fenced_call("r", [] {
      std::vector<char> huge(std::size_t{1} << 33);  // 8 GiB asked by a corrupt count
      huge[12345] = 1;
      return std::string(1, huge[12345]);
    }, limits);
    FAIL() << "no error";
  } catch (const DataError& e) {
    const std::string what = e.what();
    if (kSanitizerOwnsAllocation) {
      EXPECT_TRUE(what.rfind("r crashed on it (SIG", 0) == 0 || what.rfind("r ended without a result (exit", 0) == 0)
          << what;
    } else {
      EXPECT_NE(what.find("64 MiB"), std::string::npos) << what;
    }
  }
  limits.cpu_seconds = 1;
  try {
    (void)fenced_call("r", [] {
      volatile std::uint64_t spin = 0;
      for (;;) spin = spin + 1;  // a reader that loops
      return std::string();
    }, limits);
    FAIL() << "no error";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("CPU time"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace habuffer

namespace habuffer {
namespace {

TEST(ErrorLine, PaddingNewlinesAndTabsBecomeOneSpaceAndALongMessageIsCut) {
  EXPECT_EQ(error_line("  bad value\n\tin   'x.csv'" + std::string(500, ' ') + "line 3  "), "bad value in 'x.csv' line 3");
  const std::string line = error_line("error: " + std::string(4096, 'q'));
  EXPECT_LE(line.size(), 640u) << line;
  EXPECT_NE(line.find("(4103 bytes)"), std::string::npos) << "a cut message says how long it was: " << line;
  EXPECT_EQ(error_line("bell\x07here"), "bell\\x07here");
}

TEST(ErrorLine, AFilesystemErrorNamesItsReasonAndAnExcerptOfEachPath) {
  const std::string name = "out/" + std::string(300, 'n') + ".png";
  const std::filesystem::filesystem_error e("cannot create directories", name,
                                            std::make_error_code(std::errc::filename_too_long));
  const std::string m = filesystem_message(e);
  EXPECT_LT(m.size(), 200u) << m;
  EXPECT_NE(m.find("cannot create directories"), std::string::npos) << m;
  EXPECT_NE(m.find("(308 bytes)"), std::string::npos) << m;
  EXPECT_EQ(m.find(std::string(100, 'n')), std::string::npos) << "the name is quoted whole: " << m;
}

}  // namespace
}  // namespace habuffer
