// Careless use of files: inputs are never outputs, outputs never collide,
// only files and pipes are read, lines are bounded, and everything quoted in
// an error is short and printable.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <thread>

#include "habuffer/bounded_read.h"
#include "habuffer/csv.h"
#include "habuffer/file_roles.h"
#include "habuffer/interchange.h"
#include "habuffer/printable.h"
#include "habuffer/progress.h"
#include "habuffer/spatial_hash_file.h"

namespace habuffer {
namespace {

namespace fs = std::filesystem;

class InputSafety : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("habuffer_safety_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const auto path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string conflict(const FileRoles& roles) {
    try {
      roles.check();
    } catch (const FileConflict& e) {
      return e.what();
    }
    return {};
  }
  static std::string data_error(const std::function<void()>& f) {
    try {
      f();
    } catch (const DataError& e) {
      return e.what();
    }
    return {};
  }
  fs::path dir_;
};

TEST_F(InputSafety, AnOutputThatIsAnInputIsRefusedHoweverItIsSpelled) {
  const std::string in = write("frags.csv", "x,y,depth,rgba\n");
  fs::create_hard_link(in, path("hard.csv"));
  fs::create_symlink(in, path("soft.csv"));
  fs::create_directories(dir_ / "sub");
  const std::vector<std::string> spellings{in, path("sub/../frags.csv"), path("./frags.csv"), path("hard.csv"),
                                           path("soft.csv")};
  for (const std::string& out : spellings) {
    FileRoles roles;
    roles.input("--in", in).output("--stats", out);
    const std::string why = conflict(roles);
    EXPECT_NE(why.find("--stats"), std::string::npos) << out;
    EXPECT_NE(why.find("same file as --in (an input"), std::string::npos) << why;
  }
  // Relative spelling from the working directory.
  const fs::path cwd = fs::current_path();
  fs::current_path(dir_);
  FileRoles relative;
  relative.input("--in", in).output("--out", "frags.csv");
  EXPECT_FALSE(conflict(relative).empty());
  fs::current_path(cwd);
}

TEST_F(InputSafety, TwoOutputsOnOneFileAreRefusedButDevicesMayTakeSeveral) {
  FileRoles roles;
  roles.output("--out", path("a.csv")).output("--dump-table", path("b.csv")).output("--stats", path("./a.csv"));
  EXPECT_NE(conflict(roles).find("(two outputs)"), std::string::npos);
  FileRoles devices;
  devices.output("--out", "/dev/null").output("--stats", "/dev/null");
  EXPECT_EQ(conflict(devices), "");
  FileRoles distinct;
  distinct.input("--in", path("a.csv")).input("--offsets", path("a.csv")).output("--out", path("c.csv"));
  EXPECT_EQ(conflict(distinct), "") << "reading one file twice harms nothing";
}

TEST_F(InputSafety, EmptyOrDirectoryOutputsAreRefused) {
  FileRoles empty;
  empty.output("--heatmap depth", "");
  EXPECT_NE(conflict(empty).find("--heatmap depth: empty file name"), std::string::npos);
  FileRoles directory;
  directory.output("--out", dir_.string());
  EXPECT_NE(conflict(directory).find("is a directory"), std::string::npos);
}

TEST_F(InputSafety, OutputsThatCannotBeWrittenAreRefusedBeforeAnyWork) {
  FileRoles missing_dir;
  missing_dir.output("--out", path("nodir/lists.csv"));
  EXPECT_NE(conflict(missing_dir).find("--out: " + path("nodir/lists.csv") + " cannot be created: directory"),
            std::string::npos);
  FileRoles image;  // image writers create their directories
  image.output("--out", path("new/deeper/image.png"), true);
  EXPECT_EQ(conflict(image), "");
  const std::string file = write("plain.csv", "");
  FileRoles under_a_file;
  under_a_file.output("--heatmap depth", file + "/x.png", true);
  EXPECT_NE(conflict(under_a_file).find("is not a directory"), std::string::npos) << conflict(under_a_file);
  FileRoles fine;
  fine.output("--out", path("lists.csv")).output("--stats", file);
  EXPECT_EQ(conflict(fine), "");
}

TEST_F(InputSafety, OnlyRegularFilesAndPipesAreRead) {
  EXPECT_NE(data_error([] { check_input_file("/dev/zero", "CSV file"); }).find("is a device"), std::string::npos);
  EXPECT_NE(data_error([&] { check_input_file(dir_.string(), "CSV file"); }).find("is a directory"), std::string::npos);
  EXPECT_NE(data_error([&] { check_input_file(path("missing.csv"), "CSV file"); }).find("cannot open for reading"),
            std::string::npos);
  EXPECT_EQ(data_error([&] { check_input_file(write("ok.csv", ""), "CSV file"); }), "");
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(path("pipe")) << "x,y,depth,rgba\n0,0,0.5,1\n1,1,0.25,2\n"; });
  const auto f = read_fragments(path("pipe"), {2, 2});
  writer.join();
  EXPECT_EQ(f.size(), 2u);
  EXPECT_NE(data_error([] { read_fragments("/dev/zero", {2, 2}); }).find("/dev/zero"), std::string::npos);
}

TEST_F(InputSafety, LinesLongerThanTheLimitStopWithTheFileAndLine) {
  const std::string body = "x,y,depth,rgba\n0,0,0.5,1\n0,0,0.5," + std::string(CsvReader::kMaxLineBytes, '7') + "\n";
  const std::string why = data_error([&] { read_fragments(write("long.csv", body), {1, 1}); });
  EXPECT_NE(why.find("long.csv:3: line longer than 1048576 bytes"), std::string::npos) << why.substr(0, 200);
  EXPECT_LT(why.size(), 400u);
  // A line just under the limit is read (and fails on its field, quoted short).
  const std::string near = "x,y,depth,rgba\n0,0,0.5," + std::string(CsvReader::kMaxLineBytes - 20, '7') + "\n";
  const std::string field = data_error([&] { read_fragments(write("near.csv", near), {1, 1}); });
  EXPECT_NE(field.find(":2: field rgba: '7777"), std::string::npos) << field.substr(0, 200);
  EXPECT_NE(field.find("...' (" + std::to_string(CsvReader::kMaxLineBytes - 20) + " bytes)"), std::string::npos)
      << field.substr(0, 200);
  EXPECT_LT(field.size(), 400u);
  // No newline at all (binary data): stopped at the limit, not read whole.
  const std::string why_binary = data_error([&] { read_fragments(write("nul.csv", std::string(3u << 20, '\0')), {1, 1}); });
  EXPECT_NE(why_binary.find("nul.csv:1: line longer than"), std::string::npos);
}

TEST_F(InputSafety, ALineOfExactlyTheLimitIsReadAndOneByteMoreIsRefused) {
  const std::string head = "0,0,0.5,";
  for (const std::size_t extra : {std::size_t{0}, std::size_t{1}}) {
    const std::string line = head + std::string(CsvReader::kMaxLineBytes - head.size() + extra, '7');
    ASSERT_EQ(line.size(), CsvReader::kMaxLineBytes + extra);
    for (const bool from_file : {true, false}) {
      const std::string why = data_error([&] {
        const std::string body = "x,y,depth,rgba\n" + line + "\n";
        if (from_file) {
          read_fragments(write("edge.csv", body), {1, 1});
        } else {
          CsvReader r = CsvReader::from_text("edge.csv", body);
          r.expect_header({"x", "y", "depth", "rgba"});
          std::vector<std::string_view> fields;
          while (r.next(fields)) (void)r.u32_dec_or_hex(fields[3], "rgba");
        }
      });
      if (extra == 0)
        EXPECT_NE(why.find(":2: field rgba"), std::string::npos) << "a line of exactly the limit is read: " << why.substr(0, 120);
      else
        EXPECT_NE(why.find(":2: line longer than"), std::string::npos) << why.substr(0, 120);
    }
  }
}

TEST_F(InputSafety, RowsWithAnExtraFieldAreRefusedInEveryCsvFile) {
  EXPECT_NE(data_error([&] { read_fragments(write("f.csv", "x,y,depth,rgba\n0,0,0.5,1,9\n"), {1, 1}); })
                .find("f.csv:2: 5 fields, expected 4"),
            std::string::npos);
  EXPECT_NE(data_error([&] { read_offset_rows(write("o.csv", "ox,oy\n0,0\n1,0,2\n")); }).find("o.csv:3: 3 fields, expected 2"),
            std::string::npos);
  EXPECT_NE(data_error([&] { read_fragments(write("h.csv", "x,y,depth,rgba,extra\n"), {1, 1}); })
                .find("header is 'x,y,depth,rgba,extra'"),
            std::string::npos);
}

TEST_F(InputSafety, AUtf8ByteOrderMarkBeforeTheHeaderIsSkipped) {
  const auto f = read_fragments(write("bom.csv", "\xEF\xBB\xBFx,y,depth,rgba\n0,0,0.5,1\n"), {1, 1});
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].rgba, 1u);
  // Only before the header: a mark inside the data is a bad field.
  EXPECT_NE(data_error([&] { read_fragments(write("mid.csv", "x,y,depth,rgba\n\xEF\xBB\xBF" "0,0,0.5,1\n"), {1, 1}); })
                .find("field x: '\\xef\\xbb\\xbf0'"),
            std::string::npos);
}

// Issue 34: whole files read within bounds. Only regular files and pipes;
// a regular file's size is checked before anything is read, a pipe stopped
// at the limit; the table loader gets the same (a directory gave
// "basic_filebuf::underflow", /dev/zero ran out of memory).
TEST_F(InputSafety, WholeFilesAreReadWithinBoundsAndDevicesNever) {
  EXPECT_NE(data_error([] { (void)read_file_bounded("/dev/zero", "voxel grid", 1000); }).find("/dev/zero: is a device"),
            std::string::npos);
  EXPECT_NE(data_error([&] { (void)read_file_bounded(dir_.string(), "voxel grid", 1000); })
                .find(": is a directory, not a voxel grid"),
            std::string::npos);
  EXPECT_NE(data_error([&] { (void)read_file_bounded(path("missing"), "voxel grid", 1000); }).find("cannot open for reading"),
            std::string::npos);
  const std::string big = write("big.bin", std::string(1001, 'b'));
  EXPECT_NE(data_error([&] { (void)read_file_bounded(big, "voxel grid", 1000); })
                .find("big.bin: 1001 bytes, more than a voxel grid can be (at most 1000 bytes)"),
            std::string::npos);
  EXPECT_EQ(read_file_bounded(big, "voxel grid", 1001), std::string(1001, 'b'));
  EXPECT_EQ(read_file_bounded(write("empty.bin", ""), "voxel grid", 0), "");
  // A regular file no machine holds: refused from its size, nothing read (a sparse file takes no disk).
  const std::string sparse = path("sparse.bin");
  {
    std::ofstream(sparse, std::ios::binary).put('x');
    std::error_code ec;
    fs::resize_file(sparse, std::uint64_t{1} << 43, ec);  // 8 TiB (ext4 holds up to 16)
    if (!ec) {
      const std::string why = data_error([&] { (void)read_file_bounded(sparse, "spatial hash table", UINT64_MAX); });
      EXPECT_NE(why.find("more than this machine's"), std::string::npos) << why;
    }
  }
  // Pipes: read whole within the limit, stopped one byte past it.
  ASSERT_EQ(::mkfifo(path("pipe").c_str(), 0600), 0);
  for (const std::size_t n : {std::size_t{100}, std::size_t{101}}) {
    std::thread writer([&] { std::ofstream(path("pipe"), std::ios::binary) << std::string(n, 'p'); });
    const std::string why = data_error([&] { EXPECT_EQ(read_file_bounded(path("pipe"), "voxel grid", 100).size(), n); });
    writer.join();
    if (n == 100) EXPECT_EQ(why, "");
    else EXPECT_NE(why.find("pipe: a pipe of more than 100 bytes, more than a voxel grid can be"), std::string::npos) << why;
  }
}

TEST_F(InputSafety, TheSpatialHashTableLoaderRefusesDevicesAndDirectoriesByName) {
  // The directory first: a loader that reads it as a stream would read /dev/zero until memory ran out.
  ASSERT_NE(data_error([&] { (void)spatial::load_spatial_hash(dir_.string()); })
                .find(": is a directory, not a spatial hash table"),
            std::string::npos);
  EXPECT_NE(data_error([] { (void)spatial::load_spatial_hash("/dev/zero"); }).find("/dev/zero: is a device"),
            std::string::npos);
  EXPECT_NE(data_error([&] { (void)spatial::load_spatial_hash(write("short.tab", "HASPATL1")); })
                .find("short.tab: not a spatial hash table"),
            std::string::npos);
}

// A key CSV's header was read by opening the file a second time: a pipe gave
// its header to that read and its first row to the CSV reader.
TEST_F(InputSafety, KeyFilesAreReadOnceSoAPipeWorks) {
  ASSERT_EQ(::mkfifo(path("keys").c_str(), 0600), 0);
  std::thread writer([&] { std::ofstream(path("keys")) << "x,y,value\n1,2,7\n3,4,0x10\n"; });
  spatial::KeyFile f;
  const std::string why = data_error([&] { f = spatial::read_keys_csv(path("keys")); });
  writer.join();
  EXPECT_EQ(why, "");
  ASSERT_EQ(f.keys.size(), 2u);
  EXPECT_EQ(f.keys[1], glm::uvec3(3, 4, 0));
  EXPECT_EQ(f.values, (std::vector<std::uint32_t>{7, 16}));
  EXPECT_FALSE(f.three_d);
  const std::string header = data_error([&] { (void)spatial::read_keys_csv(write("k.csv", "x,q\n1,2\n")); });
  EXPECT_NE(header.find("k.csv:1: header is 'x,q', expected 'x,y', 'x,y,z', 'x,y,value' or 'x,y,z,value'"),
            std::string::npos)
      << header;
  EXPECT_NE(data_error([] { (void)spatial::read_keys_csv("/dev/zero"); }).find("/dev/zero: is a device"),
            std::string::npos);
}

TEST(Printable, ControlAndBinaryBytesAreEscapedAndLongTextCut) {
  EXPECT_EQ(excerpt("abc"), "'abc'");
  EXPECT_EQ(excerpt(std::string("a\0b\n\x7f\xff\\", 7)), "'a\\x00b\\x0a\\x7f\\xff\\\\'");
  EXPECT_EQ(excerpt(std::string(100, 'z'), 4), "'zzzz...' (100 bytes)");
  EXPECT_EQ(printable(std::string(300, 'q')).size(), std::string(200, 'q').size() + std::string("... (300 bytes)").size());
  for (int b = 0; b < 256; ++b) {
    const std::string e = excerpt(std::string(1, static_cast<char>(b)));
    for (char c : e) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "byte " << b;
  }
}

TEST(Progress, TheLineShowsFractionCountRateAndTimeLeft) {
  EXPECT_EQ(format_progress("stats", "trials", 0, 10, 0.0, 10), "stats [          ]   0% 0/10 trials");
  EXPECT_EQ(format_progress("stats", "trials", 5, 10, 2.0, 10), "stats [#####     ]  50% 5/10 trials, 2.5/s, 2 s left");
  EXPECT_EQ(format_progress("render", "frames", 10, 10, 4.0, 4), "render [####] 100% 10/10 frames, 2.5/s");
  EXPECT_NE(format_progress("s", "t", 1, 100000, 1.0).find("27.8 h left"), std::string::npos);
  // Disabled bars write nothing (stderr not a terminal, or --quiet).
  std::FILE* sink = std::tmpfile();
  {
    ProgressBar quiet("q", "t", false, sink);
    quiet.update(1, 2);
  }
  EXPECT_EQ(std::ftell(sink), 0L);
  {
    ProgressBar shown("q", "t", true, sink);
    shown.update(1, 2);
  }
  EXPECT_GT(std::ftell(sink), 0L);
  std::fclose(sink);
}

}  // namespace
}  // namespace habuffer
