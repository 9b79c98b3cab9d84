// Atomic writes (base/atomic_file.hpp): a process killed between the write and the rename
// leaves the old file whole and readable; a refused write leaves no temp file.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "base/atomic_file.hpp"
#include "base/error.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
namespace fs = std::filesystem;

namespace {

// The names in `dir` other than `keep` (temp files left behind).
std::vector<std::string> others(const std::string& dir, const std::string& keep) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().filename() != keep) out.push_back(e.path().filename().string());
  return out;
}

}  // namespace

TEST(AtomicFile, WriteReplacesTheFileWhole) {
  test::TempDir d;
  const std::string path = d / "f.txt";
  write_file_atomic(path, "old\n");
  EXPECT_EQ(test::slurp(path), "old\n");
  write_file_atomic(path, "new contents\n");
  EXPECT_EQ(test::slurp(path), "new contents\n");
  EXPECT_TRUE(others(d.path.string(), "f.txt").empty());  // no temp file left
}

TEST(AtomicFile, AKillBetweenWriteAndRenameLeavesTheOldFileIntact) {
  test::TempDir d;
  const std::string path = d / "state.json";
  write_file_atomic(path, "{\"old\": true}\n");
  int ready[2];
  ASSERT_EQ(::pipe(ready), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // the writer: all the new bytes written, then stopped before the rename
    ::close(ready[0]);
    AtomicFileWriter w(path);
    w.write(std::string(1 << 20, 'x'));
    const char one = 1;
    if (::write(ready[1], &one, 1) != 1) ::_exit(1);
    ::pause();  // SIGKILL arrives here, before commit()
    w.commit();
    ::_exit(0);
  }
  ::close(ready[1]);
  char got = 0;
  ASSERT_EQ(::read(ready[0], &got, 1), 1);  // the child has written everything
  ::close(ready[0]);
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
  EXPECT_EQ(test::slurp(path), "{\"old\": true}\n");  // the old file, whole
  // What a SIGKILL cannot clean up is the hidden temp file beside it, never the target.
  const auto left = others(d.path.string(), "state.json");
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].rfind(".state.json.tmp", 0), 0u) << left[0];
  EXPECT_EQ(fs::file_size(d.path / left[0]), std::uintmax_t(1) << 20);
}

TEST(AtomicFile, KillsDuringAHugeWriteLeaveTheOldOrTheNewFileNeverAMix) {
  test::TempDir d;
  const std::string path = d / "big.bin";
  const std::string old_text = "the old file\n";
  const std::size_t big = std::size_t(32) << 20;
  for (int delay_ms : {0, 2, 10, 40}) {
    write_file_atomic(path, old_text);
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      write_file_atomic(path, std::string(big, 'n'));
      ::_exit(0);
    }
    ::usleep(useconds_t(delay_ms) * 1000);
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    const std::string now = test::slurp(path);
    if (now.size() == big) {
      EXPECT_EQ(now.find_first_not_of('n'), std::string::npos) << delay_ms;  // the new file, whole
    } else {
      EXPECT_EQ(now, old_text) << delay_ms;  // or the old one, whole
    }
  }
}

TEST(AtomicFile, AWriterDestroyedBeforeCommitRemovesItsTempFile) {
  test::TempDir d;
  const std::string path = d / "p.f32";
  write_file_atomic(path, "kept");
  {
    AtomicFileWriter w(path);
    w.write("partial");
  }
  EXPECT_EQ(test::slurp(path), "kept");
  EXPECT_TRUE(others(d.path.string(), "p.f32").empty());
}

TEST(AtomicFile, AnUnwritableDirectoryIsAnInputErrorNamingThePath) {
  test::TempDir d;
  const std::string path = d / "missing-dir/f.txt";
  try {
    write_file_atomic(path, "x");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  }
  EXPECT_TRUE(others(d.path.string(), "").empty());
}
