// Outputs appear whole or not at all (habuffer/atomic_file.h): an earlier
// file survives every failure, and no temporary file is left behind.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <thread>

#include "habuffer/atomic_file.h"
#include "habuffer/atomic_folder.h"
#include "habuffer/csv.h"

namespace habuffer {
namespace {

namespace fs = std::filesystem;

class AtomicOutput : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("habuffer_atomic_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    old_ = (dir_ / "out.csv").string();
    std::ofstream(old_) << "earlier contents\n";
  }
  void TearDown() override { fs::remove_all(dir_); }
  static std::string read(const std::string& path) {
    std::ifstream in(path);
    return {std::istreambuf_iterator<char>(in), {}};
  }
  // Every file of the directory but the earlier output.
  [[nodiscard]] std::vector<std::string> others() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_))
      if (e.path().filename() != "out.csv") names.push_back(e.path().filename().string());
    return names;
  }
  // Runs `body` in a child process; its exit status.
  template <class Body>
  static int in_child(Body body) {
    const pid_t pid = ::fork();
    if (pid == 0) {
      body();
      ::_exit(0);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    return WIFEXITED(status) ? WEXITSTATUS(status) : 1000 + WTERMSIG(status);
  }
  fs::path dir_;
  std::string old_;
};

TEST_F(AtomicOutput, ACommittedFileReplacesTheEarlierOneWhole) {
  AtomicFile f(old_);
  f.write("new ");
  EXPECT_EQ(read(old_), "earlier contents\n") << "the target changed before the commit";
  f.write("contents\n");
  f.commit();
  EXPECT_EQ(read(old_), "new contents\n");
  EXPECT_TRUE(others().empty());
}

TEST_F(AtomicOutput, AFileDroppedBeforeItsCommitLeavesTheEarlierOneAndNoTemporary) {
  {
    AtomicFile f(old_);
    f.write("partial");
    EXPECT_EQ(others().size(), 1u) << "the bytes go to one temporary file beside the target";
  }
  EXPECT_EQ(read(old_), "earlier contents\n");
  EXPECT_TRUE(others().empty());
}

TEST_F(AtomicOutput, ACsvWriterThatIsNotClosedLeavesTheEarlierFile) {
  {
    CsvWriter w(old_);
    for (int i = 0; i < 200000; ++i) w.u64(static_cast<std::uint64_t>(i)).endl();  // past its 1 MiB buffer
  }
  EXPECT_EQ(read(old_), "earlier contents\n");
  EXPECT_TRUE(others().empty());
}

TEST_F(AtomicOutput, AFileSizeLimitIsAWriteErrorNamingTheReasonAndTheEarlierFileStays) {
  const std::string target = old_;
  const int status = in_child([&] {
    remove_partial_outputs_on_signals();  // SIGXFSZ ignored: the write fails instead of killing
    const rlimit limit{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      AtomicFile f(target);
      f.write(std::string(100000, 'x'));
      f.commit();
    } catch (const DataError& e) {
      ::_exit(std::string(e.what()).find("File too large") != std::string::npos ? 42 : 43);
    }
    ::_exit(44);
  });
  EXPECT_EQ(status, 42);
  EXPECT_EQ(read(old_), "earlier contents\n");
  EXPECT_TRUE(others().empty());
}

TEST_F(AtomicOutput, ADeviceIsWrittenInPlaceAndAFullOneSaysSo) {
  if (::access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no writable /dev/full";
  AtomicFile null_device("/dev/null");
  null_device.write("anything");
  null_device.commit();
  EXPECT_TRUE(fs::is_character_file("/dev/null")) << "a device must never be renamed over";
  try {
    AtomicFile full("/dev/full");
    full.write(std::string(1 << 16, 'x'));
    full.commit();
    FAIL() << "no error writing /dev/full";
  } catch (const DataError& e) {
    EXPECT_NE(std::string(e.what()).find("No space left on device"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("/dev/full"), std::string::npos) << e.what();
  }
}

TEST_F(AtomicOutput, APipeAndALinkToOneAreWrittenInPlace) {
  const std::string fifo = (dir_ / "pipe").string(), link = (dir_ / "stdout-like").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink(fifo, link);  // as /dev/stdout links to the process's pipe
  for (const std::string& target : {fifo, link}) {
    std::string got;
    std::thread reader([&] { got = read(fifo); });
    {
      AtomicFile f(target);
      f.write("through the pipe\n");
      f.commit();
    }
    reader.join();
    EXPECT_EQ(got, "through the pipe\n") << target;
    EXPECT_TRUE(fs::is_fifo(fifo));
  }
  EXPECT_TRUE(fs::is_symlink(link));
}

TEST_F(AtomicOutput, ASymbolicLinkStaysALinkToTheReplacedFile) {
  const std::string link = (dir_ / "link.csv").string();
  fs::create_symlink("out.csv", link);
  AtomicFile f(link);
  f.write("through the link\n");
  f.commit();
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read(old_), "through the link\n");
}

TEST_F(AtomicOutput, AReplacedFileKeepsItsPermissionBits) {
  ::chmod(old_.c_str(), 0640);
  AtomicFile f(old_);
  f.write("x\n");
  f.commit();
  struct stat st {};
  ASSERT_EQ(::stat(old_.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0640u);
}

TEST_F(AtomicOutput, AFileWrittenByNameIsStagedUnderTheTargetsExtension) {
  const std::string image = (dir_ / "picture.png").string();
  AtomicFile f(image, AtomicFile::Access::ByName);
  EXPECT_EQ(fs::path(f.staging_path()).extension(), ".png");
  EXPECT_EQ(fs::path(f.staging_path()).parent_path(), dir_);
  std::ofstream(f.staging_path()) << "pixels";
  EXPECT_FALSE(fs::exists(image));
  f.commit();
  EXPECT_EQ(read(image), "pixels");
}

TEST_F(AtomicOutput, ASignalMidWriteRemovesTheTemporaryAndExitsWith128PlusTheSignal) {
  const std::string target = old_;
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    const int status = in_child([&] {
      remove_partial_outputs_on_signals();
      AtomicFile f(target);
      f.write("partial");
      ::raise(sig);
      ::_exit(1);
    });
    EXPECT_EQ(status, 128 + sig) << "signal " << sig;
    EXPECT_EQ(read(old_), "earlier contents\n");
    EXPECT_TRUE(others().empty()) << "signal " << sig << " left " << others().front();
  }
}

// A committed (or dropped) file frees its slot in the signal handler's
// registry (issue 46, part 8): after more files than the registry has
// slots, a file mid-write is still removed by a signal.
TEST_F(AtomicOutput, CommittedFilesFreeTheirSignalSlotsSoALaterTemporaryIsStillRemoved) {
  const std::string target = old_;
  const fs::path dir = dir_;
  const int status = in_child([&] {
    remove_partial_outputs_on_signals();
    for (int i = 0; i < 600; ++i) {  // more than the registry's 256 slots, committed and dropped
      AtomicFile f((dir / ("done" + std::to_string(i % 3) + ".csv")).string());
      f.write("x");
      if (i % 2 == 0) f.commit();
    }
    AtomicFile f(target);
    f.write("partial");
    ::raise(SIGTERM);
    ::_exit(1);
  });
  EXPECT_EQ(status, 128 + SIGTERM);
  EXPECT_EQ(read(old_), "earlier contents\n");
  for (const std::string& name : others())
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "a temporary left behind: " << name;
}

TEST_F(AtomicOutput, ADirectoryOrAnEmptyNameIsRefusedNamingIt) {
  EXPECT_THROW(AtomicFile(dir_.string()), DataError);
  EXPECT_THROW(AtomicFile(""), DataError);
  EXPECT_THROW(AtomicFile((dir_ / "missing" / "x.csv").string()), DataError);
}

TEST_F(AtomicOutput, AWriteThroughADanglingLinkCreatesItsTargetAndKeepsTheLink) {
  const std::string link = (dir_ / "dangling.csv").string();
  fs::create_symlink("made.csv", link);
  AtomicFile f(link);
  f.write("new\n");
  f.commit();
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(read((dir_ / "made.csv").string()), "new\n");
}

// An earlier set of slices in `folder`: `count` members.
void make_set(const fs::path& folder, int count, const std::string& text) {
  fs::create_directories(folder);
  for (int i = 0; i < count; ++i) std::ofstream(folder / ("slice_" + std::to_string(1000 + i) + ".png")) << text;
}

TEST_F(AtomicOutput, ACommittedSetReplacesALargerEarlierSetWholeAndLeavesNoStaleMember) {
  const fs::path folder = dir_ / "slices";
  make_set(folder, 8, "old");
  AtomicFolder set(folder.string(), "slice_*.png");
  for (int i = 0; i < 3; ++i) std::ofstream(set.member("slice_" + std::to_string(1000 + i) + ".png")) << "new";
  EXPECT_EQ(read((folder / "slice_1000.png").string()), "old");  // nothing visible before the commit
  set.commit();
  int members = 0;
  for (const auto& e : fs::directory_iterator(folder)) {
    ++members;
    EXPECT_EQ(read(e.path().string()), "new");
  }
  EXPECT_EQ(members, 3);
  EXPECT_EQ(others(), std::vector<std::string>{"slices"});  // no temporary folder beside it
}

TEST_F(AtomicOutput, ASetDroppedBeforeItsCommitLeavesTheEarlierSetAndNoTemporary) {
  const fs::path folder = dir_ / "slices";
  make_set(folder, 4, "old");
  {
    AtomicFolder set(folder.string(), "slice_*.png");
    std::ofstream(set.member("slice_1000.png")) << "new";
  }
  EXPECT_EQ(read((folder / "slice_1000.png").string()), "old");
  EXPECT_EQ(others(), std::vector<std::string>{"slices"});
}

TEST_F(AtomicOutput, ASetRefusesAFolderHoldingOtherFilesAndAFile) {
  const fs::path folder = dir_ / "mine";
  make_set(folder, 2, "old");
  std::ofstream(folder / "notes.txt") << "mine";
  EXPECT_NE(output_set_conflict(folder.string(), "slice_*.png").find("notes.txt"), std::string::npos);
  EXPECT_THROW(AtomicFolder(folder.string(), "slice_*.png"), DataError);
  EXPECT_EQ(read((folder / "notes.txt").string()), "mine");
  EXPECT_NE(output_set_conflict(old_, "slice_*.png").find("is a file"), std::string::npos);
}

TEST_F(AtomicOutput, ASignalWhileASetIsWrittenLeavesTheEarlierSetWholeAndNoTemporary) {
  const fs::path folder = dir_ / "slices";
  make_set(folder, 5, "old");
  for (const int sig : {SIGINT, SIGTERM}) {
    const int status = in_child([&] {
      remove_partial_outputs_on_signals();
      AtomicFolder set(folder.string(), "slice_*.png");
      for (int i = 0; i < 3; ++i) std::ofstream(set.member("slice_" + std::to_string(1000 + i) + ".png")) << "new";
      ::raise(sig);
      ::_exit(1);
    });
    EXPECT_EQ(status, 128 + sig);
    int members = 0;
    for (const auto& e : fs::directory_iterator(folder)) {
      ++members;
      EXPECT_EQ(read(e.path().string()), "old");
    }
    EXPECT_EQ(members, 5);
    EXPECT_EQ(others(), std::vector<std::string>{"slices"});
  }
}

}  // namespace
}  // namespace habuffer
