// Faults while writing: a full disk (an RLIMIT_FSIZE child: every write past the limit fails with
// EFBIG, SIGXFSZ ignored) for every writing command is exit 2 with the old outputs as they were,
// no hidden temp file and no database created; SIGTERM and SIGINT the moment a command's first
// temp file appears (inotify) leave no hidden temp file either.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/inotify.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "base/hash.hpp"
#include "tests/build_paths.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> split_words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> words;
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

// Every file under `dir` and a hash of its bytes.
std::map<std::string, std::uint64_t> fault_snapshot(const fs::path& dir) {
  std::map<std::string, std::uint64_t> m;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string bytes = e.is_regular_file() ? slurp(e.path().string()) : std::string();
    m[fs::relative(e.path(), dir).string()] = tilekit::StableHash().add(std::string_view(bytes)).fnv();
  }
  return m;
}

std::vector<std::string> hidden_files(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().starts_with(".")) out.push_back(e.path().string());
  return out;
}

// `tilekit args` with every file it writes limited to `bytes` (a full disk) and SIGXFSZ ignored,
// so that a write past the limit fails with EFBIG as on a full disk.
CliResult run_with_file_limit(const std::vector<std::string>& args, rlim_t bytes, const TempDir& logs) {
  const std::string out = logs / "stdout", err = logs / "stderr";
  const pid_t pid = fork();
  if (pid == 0) {
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int n = ::open("/dev/null", O_RDONLY);
    if (o < 0 || e < 0 || n < 0) _exit(120);
    ::dup2(n, 0), ::dup2(o, 1), ::dup2(e, 2);
    const struct rlimit lim { bytes, bytes };
    ::setrlimit(RLIMIT_FSIZE, &lim);
    ::signal(SIGXFSZ, SIG_IGN);
    std::vector<std::string> all{TILEKIT_BINARY};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    _exit(121);
  }
  CliResult r;
  r.code = pid > 0 ? wait_exit(pid) : -1;
  r.out = slurp(out);
  r.err = slurp(err);
  return r;
}

// The files the commands read and the old outputs they must leave alone, made once.
class IoFaults : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new TempDir;
    const TempDir& d = *dir_;
    fs::copy_file(std::string(source_dir()) + "/aperiodic/data/finite-14.tiles", d / "S.tiles");
    for (const std::string& m : std::vector<std::string>{
             "pack --kind corner --colors 3 --db " + (d / "R.sqlite") + " --quiet",
             "tile --set complete-corner-4 --algo direct --size 12x12 --tile-size 10 --out " + (d / "I.png"),
             "points tiles --colors 2 --points 16 --no-db --out " + (d / "P.txt") + " --quiet",
             "texture tiles --exemplar " + (d / "I.png") + " --colors 2 --tile-px 16 --search 2 --out " + (d / "T") +
                 " --quiet",
             "texture atlas " + (d / "T") + " --out " + (d / "A.png") + " --no-db"}) {
      const CliResult r = run_cli(m);
      ASSERT_EQ(r.code, 0) << m << "\n" << r.err;
    }
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static TempDir* dir_;
};
TempDir* IoFaults::dir_ = nullptr;

// Every writing command on a full disk: exit 2, one line, the old outputs (made by a run without the
// limit) unchanged, no hidden temp file, and no new database.
TEST_F(IoFaults, AFullDiskIsExitTwoWithTheOldOutputsKeptForEveryWritingCommand) {
  const TempDir& d = *dir_;
  struct Case {
    std::string args;     // "@": the input folder, "%": the output folder
    bool remake = true;   // run once without the limit first, so that the old outputs exist
    rlim_t limit = 2048;  // bytes per file: less than the output (and more than the one stderr line)
  };
  const std::vector<Case> cases = {
      {"tile --set complete-corner-4 --algo direct --size 200x200 --out %/t.json"},
      {"tile --set complete-corner-4 --algo direct --size 100x100 --tile-size 4 --out %/t.png"},
      {"tileset show complete-corner-4 --out %/s.svg"},
      {"db export --db @/R.sqlite --out %/e.json"},
      {"atlas lookup --kind corner --colors 8 --no-db --format c --out %/l.h"},
      {"atlas build --kind corner --colors 4 --no-db --tile-size 16 --out %/b.png"},
      {"aperiodic convert @/S.tiles --method diagonal --out %/c.tiles", true, 256},
      {"points tiles --colors 2 --points 64 --no-db --out %/p.txt --picture %/p.png --quiet"},
      {"points generate --tiles @/P.txt --window 0,0,40,40 --density 20 --out %/g.csv --quiet"},
      {"points generate --tiles @/P.txt --window 0,0,40,40 --density 20 --out %/g.f32 --quiet"},
      {"points analyze %/g.csv --window 0,0,40,40 --plot %/a.png --spectrum %/sp.png", false},
      {"texture tiles --exemplar @/I.png --colors 3 --tile-px 16 --search 2 --out %/T --quiet"},
      {"texture atlas @/T --out %/A.png --no-db"},
      {"texture render --atlas @/A.png --size 200x200 --out %/r.png --quiet"},
      {"texture preview --atlas @/A.png --out %/p.html"},
      {"texture analyze @/I.png --tile-px 16 --plot %/an.png"},
      {"tiled tileset --colors 2 --tiles @/T --out %/tiled"},
      {"pack --kind corner --colors 3 --mode all --db %/new.sqlite --quiet", false},
      {"points recursive --points 16 --db %/new2.sqlite --out %/rec.txt --quiet", false},
      {"db merge %/m.sqlite @/R.sqlite", false},
  };
  TempDir out, logs;
  for (const Case& c : cases) {
    std::string args = c.args;
    for (std::size_t p; (p = args.find_first_of("@%")) != std::string::npos;)
      args.replace(p, 1, args[p] == '@' ? d.path.string() : out.path.string());
    const std::vector<std::string> words = split_words(args);
    if (c.remake) {
      const CliResult first = run_cli(args);
      ASSERT_EQ(first.code, 0) << args << "\n" << first.err;
    }
    const auto before = fault_snapshot(out.path);
    const CliResult r = run_with_file_limit(words, c.limit, logs);
    EXPECT_EQ(r.code, 2) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_EQ(fault_snapshot(out.path), before) << args << "\n" << r.err;
    EXPECT_EQ(hidden_files(out.path), std::vector<std::string>{}) << args;
  }
  // The issue's case: a refused `pack --mode all` leaves no header-only database.
  EXPECT_FALSE(fs::exists(out / "new.sqlite"));
  EXPECT_FALSE(fs::exists(out / "m.sqlite"));
}

// A full disk under an existing database: the pack's run is rolled back and the database is as it
// was (SQLite may keep an empty write-ahead log and its index beside it, as after any connection
// that could not checkpoint on close).
TEST_F(IoFaults, AFullDiskUnderAnExistingDatabaseLeavesItAsItWas) {
  const TempDir& d = *dir_;
  TempDir out, logs;
  fs::copy_file(d / "R.sqlite", out / "R.sqlite");
  const auto before = fault_snapshot(out.path);
  const CliResult r = run_with_file_limit(
      {"pack", "--kind", "corner", "--colors", "2", "--mode", "all", "--db", out / "R.sqlite", "--quiet"}, 2048, logs);
  EXPECT_EQ(r.code, 2) << r.err;
  auto after = fault_snapshot(out.path);
  if (fs::exists(out / "R.sqlite-wal")) {
    EXPECT_EQ(fs::file_size(out / "R.sqlite-wal"), 0u);
  }
  after.erase("R.sqlite-wal"), after.erase("R.sqlite-shm");
  EXPECT_EQ(after, before) << r.err;
  EXPECT_EQ(hidden_files(out.path), std::vector<std::string>{});
}

// The database is written last: `pack --out` on a disk that takes the packing's rows but not the
// file (a 600 KB limit; the C=16 packing's JSON is about 650 KB) stores nothing.
TEST_F(IoFaults, APackWhoseOutputCannotBeWrittenStoresNothing) {
  const TempDir& d = *dir_;
  TempDir out, logs;
  fs::copy_file(d / "R.sqlite", out / "R.sqlite");
  const std::string exported = run_cli("db export --db " + (out / "R.sqlite")).out;
  ASSERT_FALSE(exported.empty());
  const CliResult r = run_with_file_limit(
      {"pack", "--kind", "corner", "--colors", "16", "--db", out / "R.sqlite", "--out", out / "p.json", "--quiet"},
      600000, logs);
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("p.json"), std::string::npos) << r.err;
  EXPECT_EQ(run_cli("db export --db " + (out / "R.sqlite")).out, exported);
  EXPECT_FALSE(fs::exists(out / "p.json"));
  EXPECT_EQ(hidden_files(out.path), std::vector<std::string>{});
}

// A rerun of `texture tiles` into the folder of a larger old set replaces it whole: no stale tile
// stays, and `texture atlas` takes the fresh set.
TEST_F(IoFaults, ASmallerTileSetReplacesALargerOneWhole) {
  const TempDir& d = *dir_;
  TempDir out;
  const auto tiles = [&](int colours) {
    return run_cli("texture tiles --exemplar " + (d / "I.png") + " --colors " + std::to_string(colours) +
                   " --tile-px 16 --search 2 --quiet --out " + (out / "T"));
  };
  ASSERT_EQ(tiles(3).code, 0);
  const CliResult r = tiles(2);
  ASSERT_EQ(r.code, 0) << r.err;
  int pngs = 0;
  for (const auto& e : fs::directory_iterator(out / "T")) pngs += e.path().filename().string().starts_with("tile-");
  EXPECT_EQ(pngs, 16);
  const CliResult a = run_cli("texture atlas " + (out / "T") + " --out " + (out / "A.png") + " --no-db");
  EXPECT_EQ(a.code, 0) << a.err;
  EXPECT_EQ(hidden_files(out.path), std::vector<std::string>{});
}

// Starts `tilekit args`, sends `sig` the moment the first hidden file appears in `watch` (the
// first temp file; inotify), and returns the exit code, or -1 if no temp file appeared.
int signal_at_first_temp(const std::vector<std::string>& args, const std::string& watch, int sig, const TempDir& logs) {
  const int in = inotify_init1(IN_CLOEXEC);
  if (in < 0 || inotify_add_watch(in, watch.c_str(), IN_CREATE) < 0) return -2;
  const pid_t pid = spawn_tilekit(args, logs / "stdout", logs / "stderr");
  bool sent = false;
  alignas(struct inotify_event) char buf[4096];
  while (!sent) {
    struct pollfd p {
      in, POLLIN, 0
    };
    if (poll(&p, 1, 60000) <= 0) break;
    const ssize_t n = read(in, buf, sizeof buf);
    for (ssize_t off = 0; off < n && !sent;) {
      const auto* e = reinterpret_cast<const struct inotify_event*>(buf + off);
      off += ssize_t(sizeof(struct inotify_event) + e->len);
      if (e->len > 0 && e->name[0] == '.') sent = kill(pid, sig) == 0;
    }
  }
  close(in);
  const int code = wait_exit(pid);
  return sent ? code : -1;
}

class IoFaultSignals : public IoFaults, public ::testing::WithParamInterface<int> {};
INSTANTIATE_TEST_SUITE_P(TermAndInt, IoFaultSignals, ::testing::Values(SIGTERM, SIGINT),
                         [](const auto& info) { return std::string(info.param == SIGTERM ? "SIGTERM" : "SIGINT"); });

// The issue's commands, each signalled while its temp file is being written: exit 3 (or 0 where the
// file was already in place), nothing hidden left, and an old output whole.
TEST_P(IoFaultSignals, NoHiddenTempFileOutlivesASignal) {
  const TempDir& d = *dir_;
  struct Case {
    std::string args;
    bool big;  // the write takes long enough that the signal must land in it
  };
  const std::vector<Case> cases = {
      {"tile --set complete-corner-4 --algo direct --size 1500x1500 --out %/t.json", true},
      {"db export --db @/R.sqlite --out %/e.json", false},
      {"atlas lookup --kind corner --colors 16 --no-db --format json --out %/l.json", false},
      {"texture atlas @/T --out %/A.png --no-db", false},
      {"points generate --tiles @/P.txt --window 0,0,200,200 --density 100 --out %/g.f32 --quiet", true},
      {"texture tiles --exemplar @/I.png --colors 3 --tile-px 32 --search 2 --out %/T --quiet", true},
  };
  TempDir out, logs;
  for (const Case& c : cases) {
    std::string args = c.args;
    for (std::size_t p; (p = args.find_first_of("@%")) != std::string::npos;)
      args.replace(p, 1, args[p] == '@' ? d.path.string() : out.path.string());
    const int code = signal_at_first_temp(split_words(args), out.path.string(), GetParam(), logs);
    const std::string err = slurp(logs / "stderr");
    EXPECT_NE(code, -1) << args << ": no temp file appeared\n" << err;
    if (c.big) {
      EXPECT_EQ(code, 3) << args << "\n" << err;
    }
    EXPECT_TRUE(code == 0 || code == 3) << args << ": " << code << "\n" << err;
    if (code == 3) {
      EXPECT_NE(err.find("interrupted by"), std::string::npos) << args << "\n" << err;
    }
    EXPECT_EQ(hidden_files(out.path), std::vector<std::string>{}) << args;
  }
}

}  // namespace
