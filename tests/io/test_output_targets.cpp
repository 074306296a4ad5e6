// Output paths that are not regular files (io/atomic_file.hpp): a FIFO and a
// device are written through, never replaced; a symbolic link's file is
// replaced and the link stays; a link to nothing is refused. Every file,
// FIFO and device node here is the test's own, in a private folder it makes
// and removes (never the machine's /dev).
#include <fcntl.h>
#include <sys/stat.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <gtest/gtest.h>

#include "core/input_error.hpp"
#include "io/atomic_file.hpp"
#include "io/read_file.hpp"
#include "io/scene_file.hpp"

namespace contact2d {
namespace {

namespace fs = std::filesystem;

class OutputTargets : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("contact2d_targets_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  // The folder holds only these names (no temporary left behind).
  void expect_only(std::vector<std::string> names) const {
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir_)) found.push_back(e.path().filename());
    std::sort(found.begin(), found.end());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(found, names);
  }
  fs::path dir_;
};

void write(const std::string& path, const std::string& text) {
  check_output_file("--csv", path);
  AtomicFile out(path);
  std::fputs(text.c_str(), out.get());
  out.commit();
}

TEST_F(OutputTargets, AFifoIsWrittenThroughAndStaysAFifo) {
  const std::string fifo = (dir_ / "pipe").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo);
    std::ostringstream text;
    text << in.rdbuf();
    received = text.str();
  });
  write(fifo, "t,x\n0,1\n");
  reader.join();
  EXPECT_EQ(received, "t,x\n0,1\n");
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  expect_only({"pipe"});
}

TEST_F(OutputTargets, ADeviceIsWrittenThroughAndStaysADevice) {
  // A node of the null device (1, 3), made here; creating one needs root.
  const std::string node = (dir_ / "null").string();
  if (::mknod(node.c_str(), S_IFCHR | 0666, makedev(1, 3)) != 0)
    GTEST_SKIP() << "cannot make a device node here (not root): " << std::strerror(errno);
  write(node, "t,x\n0,1\n");
  struct stat st {};
  ASSERT_EQ(::lstat(node.c_str(), &st), 0);
  EXPECT_TRUE(S_ISCHR(st.st_mode));
  EXPECT_EQ(st.st_rdev, makedev(1, 3));
  expect_only({"null"});
}

TEST_F(OutputTargets, ASymlinksFileIsReplacedAndTheLinkStays) {
  std::ofstream(dir_ / "data.csv") << "old\n";
  fs::create_symlink("data.csv", dir_ / "link.csv");
  write((dir_ / "link.csv").string(), "new\n");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(dir_ / "link.csv")));
  std::ifstream in(dir_ / "data.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line, "new");
  expect_only({"data.csv", "link.csv"});
}

TEST_F(OutputTargets, ALinkToNothingIsRefusedInOneLine) {
  fs::create_symlink("missing.csv", dir_ / "dangling.csv");
  try {
    check_output_file("--csv", (dir_ / "dangling.csv").string());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("a symbolic link to a file that does not exist"),
              std::string::npos)
        << e.what();
  }
  expect_only({"dangling.csv"});
}

TEST_F(OutputTargets, AFailedRunWritesNothingThroughAFifo) {
  const std::string fifo = (dir_ / "pipe").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  {
    AtomicFile out(fifo);
    std::fputs("half a run", out.get());
  }  // not committed: nothing opens the FIFO (no reader is needed, none waits)
  expect_only({"pipe"});
}

}  // namespace
}  // namespace contact2d

namespace contact2d {
namespace {

// Input files are read bounded (io/read_file.hpp): a scene file past 4 MiB
// (here a private file of 5 MiB of comment lines, standing for /dev/zero or
// a file given by mistake) is one line, not a read until memory runs out.
TEST(InputFiles, AHugeSceneFileIsRefusedInOneLine) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() /
                                     ("contact2d_huge_" + std::to_string(::getpid()) + ".toml");
  {
    std::ofstream out(path);
    const std::string line(1023, '#');
    for (int i = 0; i < 5 * 1024; ++i) out << line << '\n';
  }
  try {
    load_scene(path.string());
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot read scene file (larger than 4 MiB"), std::string::npos) << what;
    EXPECT_EQ(what.find('\n'), std::string::npos);
  }
  std::filesystem::remove(path);
}

// A FIFO (the test's own) no process opened for writing: open() without
// O_NONBLOCK blocked without end (`fit` on such a recording's CSV, a
// scene given as one). Now refused at once, in one line.
TEST_F(OutputTargets, AFifoNobodyWritesIsRefusedAtOnce) {
  const std::string fifo = (dir_ / "scene.toml").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const auto start = std::chrono::steady_clock::now();
  try {
    read_input_file(fifo, "scene file");
    ADD_FAILURE() << "read";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              fifo + ": cannot read scene file (a pipe nobody was writing to)");
  }
  // At once: no wait at all is involved (generous for a loaded machine).
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2.0);
}

// A pipe whose writer holds it open and writes nothing (here this test:
// a FIFO opened read-write counts as a writer, and opening it so does not
// block) is given up at the read's deadline, 0.3 s here (10 s in the
// program, io/read_file.hpp), with one line; a pipe whose writer writes
// later and closes is read whole, as a shell's <(command) is.
TEST_F(OutputTargets, APipeIsReadUntilItsWriterClosesButNotWaitedOnWithoutEnd) {
  const std::string fifo = (dir_ / "scene.toml").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  {
    const int writer = ::open(fifo.c_str(), O_RDWR | O_CLOEXEC);
    ASSERT_GE(writer, 0) << std::strerror(errno);
    const auto start = std::chrono::steady_clock::now();
    try {
      read_input_file(fifo, "scene file", kMaxInputBytes, "too large", 0.3);
      ADD_FAILURE() << "read";
    } catch (const InputError& e) {
      EXPECT_EQ(std::string(e.what()),
                fifo +
                    ": cannot read scene file (nothing came within 0.3 s: a pipe or device "
                    "nobody writes to the end)");
    }
    const double waited =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_GE(waited, 0.3);
    EXPECT_LT(waited, 1.3);  // the deadline, and 1 s for a loaded machine
    ::close(writer);
  }
  {
    const int writer = ::open(fifo.c_str(), O_RDWR | O_CLOEXEC);
    ASSERT_GE(writer, 0) << std::strerror(errno);
    std::thread later([writer] {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));  // the reader waits
      const std::string text = "scene = \"box\"\n";
      EXPECT_EQ(::write(writer, text.data(), text.size()), static_cast<ssize_t>(text.size()));
      ::close(writer);
    });
    std::string read;
    EXPECT_NO_THROW(read = read_input_file(fifo, "scene file", kMaxInputBytes, "too large", 5.0));
    later.join();
    EXPECT_EQ(read, "scene = \"box\"\n");
  }
}

}  // namespace
}  // namespace contact2d
