// fuzz_driver: the harnesses of fuzz/ (each a libFuzzer entry point, LLVMFuzzerTestOneInput) run
// by a plain C++ mutation loop, in the ordinary Release build (g++, -O3, asserts on): no clang, no
// sanitizer, no coverage feedback. scripts/test.sh runs it (scripts/fuzz.sh --driver) so that the
// README's command fuzzes every parser without the separate ASan libFuzzer build, which .ci/run
// runs next (scripts/test.sh --sanitize). What it finds: crashes (SIGSEGV, SIGBUS, SIGFPE, SIGILL),
// failed asserts and the harnesses' own property checks (std::abort), uncaught exceptions, hangs
// and runaway memory. What only the libFuzzer build finds: memory errors that do not crash, leaks,
// undefined behaviour, and inputs that need coverage guidance to be reached.
//
//   fuzz_driver NAME [-max_total_time=S] [-runs=N] [-seed=N] [-max_len=B] [-timeout=S]
//               [-rss_limit_mb=M] [-artifact_prefix=DIR/] CORPUS_DIR_OR_FILE...
//
// Runs every input of the corpus (the files of each directory, and files named, sorted by path)
// once, then mutants of them until S seconds or N runs in all have passed, whichever comes first
// (0: no such bound; with both 0, the corpus only): each mutant is 1 to 5
// libFuzzer-style mutations (bytes erased, inserted, changed, repeated or shuffled, a bit flipped,
// an ASCII number or a binary integer replaced by an edge value, a part copied, a splice with
// another input, a syntax token inserted) of a corpus input or, one time in four, of the mutant
// before it. The sequence of inputs depends only on the seed and the corpus. A crash writes the
// input to DIR/crash-HASH and ends the process by the same signal; an input running longer than the
// timeout is written to DIR/timeout-HASH (exit 70), one that takes the resident memory past M MiB
// to DIR/oom-HASH (exit 71). The last lines are libFuzzer's (stat::number_of_executed_units,
// "Done N runs in S second(s)"), which scripts/fuzz.sh reads.
#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <random>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "fuzz/driver_harnesses.hpp"

namespace {

using Bytes = std::vector<std::uint8_t>;
using Clock = std::chrono::steady_clock;

// ---- the input being run, for the crash handler and the watchdog ---------------------------------
std::atomic<const std::uint8_t*> g_data{nullptr};
std::atomic<std::size_t> g_size{0};
std::atomic<std::int64_t> g_started_ms{-1};  // start of the run in progress; -1 between runs
char g_prefix[4096] = "./";

std::int64_t now_ms() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now().time_since_epoch()).count();
}

// Writes the input being run to g_prefix + kind + "-" + its FNV-1a hash, and says so on stderr.
// Only async-signal-safe calls: it runs in the crash handler.
void write_artifact(const char* kind, const char* why) {
  const std::uint8_t* data = g_data.load();
  const std::size_t size = g_size.load();
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < size; ++i) h = (h ^ data[i]) * 1099511628211ull;
  char path[4200];
  std::size_t n = 0;
  for (const char* p = g_prefix; *p && n < 4096; ++p) path[n++] = *p;
  for (const char* p = kind; *p; ++p) path[n++] = *p;
  path[n++] = '-';
  for (int i = 15; i >= 0; --i) path[n++] = "0123456789abcdef"[(h >> (4 * i)) & 15];
  path[n] = 0;
  const int fd = ::open(path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd >= 0) {
    std::size_t done = 0;
    while (done < size) {
      const ssize_t w = ::write(fd, data + done, size - done);
      if (w <= 0) break;
      done += std::size_t(w);
    }
    ::close(fd);
  }
  auto say = [](const char* s) { [[maybe_unused]] ssize_t r = ::write(2, s, std::strlen(s)); };
  say("==fuzz_driver== ");
  say(why);
  say("; the input is in ");
  say(path);
  say("\n");
}

void on_crash(int sig) {
  write_artifact("crash", sig == SIGABRT   ? "abort (a failed assert or property check, or an uncaught exception)"
                          : sig == SIGSEGV ? "SIGSEGV"
                          : sig == SIGBUS  ? "SIGBUS"
                          : sig == SIGFPE  ? "SIGFPE"
                                           : "SIGILL");
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void install_crash_handlers() {
  static std::vector<char> alt(1 << 16);  // a stack overflow still reaches the handler
  stack_t ss{};
  ss.ss_sp = alt.data();
  ss.ss_size = alt.size();
  ::sigaltstack(&ss, nullptr);
  struct sigaction sa {};
  sa.sa_handler = on_crash;
  sa.sa_flags = SA_ONSTACK;
  ::sigemptyset(&sa.sa_mask);
  for (int sig : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) ::sigaction(sig, &sa, nullptr);
}

std::size_t resident_mib() {
  std::ifstream in("/proc/self/statm");
  std::size_t pages = 0, resident = 0;
  in >> pages >> resident;
  return resident * std::size_t(::sysconf(_SC_PAGESIZE)) >> 20;
}

// Every 100 ms: is the run in progress over the timeout, is the process over the memory limit?
void watchdog(int timeout_s, std::size_t rss_limit_mib) {
  for (;;) {
    std::this_thread::sleep_for(std::chrono::milliseconds(100));
    const std::int64_t started = g_started_ms.load();
    if (timeout_s > 0 && started >= 0 && now_ms() - started > std::int64_t(timeout_s) * 1000) {
      write_artifact("timeout", "an input ran past -timeout");
      std::_Exit(70);
    }
    if (rss_limit_mib > 0 && resident_mib() > rss_limit_mib) {
      write_artifact("oom", "the resident memory passed -rss_limit_mb");
      std::_Exit(71);
    }
  }
}

// ---- mutations ---------------------------------------------------------------------------------
struct Mutator {
  std::mt19937_64 rng;
  const std::vector<Bytes>& corpus;
  std::size_t max_len;

  std::size_t below(std::size_t n) { return n == 0 ? 0 : std::size_t(rng() % n); }
  std::uint8_t byte() { return std::uint8_t(rng()); }

  // Syntax of the inputs the harnesses read (JSON, tile-set text, specs, flags) and edge values.
  static const std::vector<std::string_view>& tokens() {
    static const std::vector<std::string_view> t{
        "{", "}", "[", "]", "\"", ":", ",", "null", "true", "false", "-", "0", "-1", "1e308", "1e999", "-0",
        "nan", "inf", "4294967296", "18446744073709551616", "9223372036854775807", "\\u0000", "\\", "\n", " ",
        "#", "=", ";", "/", "x", "(", ")", "*", "^", "e", ".", "\"\":", "{}", "[]", "wang", "corner", "pi", "t=0,"};
    return t;
  }

  void erase(Bytes& d) {
    if (d.empty()) return;
    const std::size_t at = below(d.size()), n = 1 + below(std::min<std::size_t>(d.size() - at, 16));
    d.erase(d.begin() + std::ptrdiff_t(at), d.begin() + std::ptrdiff_t(at + n));
  }
  void insert(Bytes& d) {
    const std::size_t at = below(d.size() + 1), n = 1 + below(rng() % 4 ? 4 : 128);
    const std::uint8_t b = byte();
    const bool repeat = rng() % 2;
    Bytes ins(n);
    for (auto& x : ins) x = repeat ? b : byte();
    d.insert(d.begin() + std::ptrdiff_t(at), ins.begin(), ins.end());
  }
  void change_byte(Bytes& d) {
    if (!d.empty()) d[below(d.size())] = byte();
  }
  void flip_bit(Bytes& d) {
    if (!d.empty()) d[below(d.size())] ^= std::uint8_t(1u << below(8));
  }
  void shuffle(Bytes& d) {
    if (d.size() < 2) return;
    const std::size_t at = below(d.size() - 1), n = 2 + below(std::min<std::size_t>(d.size() - at - 1, 7));
    std::shuffle(d.begin() + std::ptrdiff_t(at), d.begin() + std::ptrdiff_t(at + n), rng);
  }
  void ascii_number(Bytes& d) {  // a run of digits replaced by a nearby or an edge value
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i < d.size(); ++i)
      if (std::isdigit(d[i]) && (i == 0 || !std::isdigit(d[i - 1]))) starts.push_back(i);
    if (starts.empty()) return insert_token(d);
    const std::size_t at = starts[below(starts.size())];
    std::size_t end = at;
    while (end < d.size() && std::isdigit(d[end])) ++end;
    const std::string old(d.begin() + std::ptrdiff_t(at), d.begin() + std::ptrdiff_t(end));
    static const char* edges[] = {"0", "1", "2", "255", "256", "65535", "65536", "2147483647", "2147483648",
                                  "4294967295", "4294967296", "9223372036854775807", "99999999999999999999", "00"};
    std::string now;
    switch (below(4)) {
      case 0: now = edges[below(std::size(edges))]; break;
      case 1: now = std::to_string(std::strtoull(old.c_str(), nullptr, 10) + 1); break;
      case 2: now = std::to_string(std::strtoull(old.c_str(), nullptr, 10) - 1); break;
      default: now = std::to_string(rng() >> below(64)); break;
    }
    d.erase(d.begin() + std::ptrdiff_t(at), d.begin() + std::ptrdiff_t(end));
    d.insert(d.begin() + std::ptrdiff_t(at), now.begin(), now.end());
  }
  void binary_integer(Bytes& d) {  // 1, 2, 4 or 8 bytes overwritten by an edge value
    const std::size_t width = std::size_t(1) << below(4);
    if (d.size() < width) return change_byte(d);
    static const std::uint64_t edges[] = {0, 1, 0x7f, 0x80, 0xff, 0x7fff, 0x8000, 0xffff, 0x7fffffff, 0x80000000,
                                          0xffffffff, 0x7fffffffffffffffull, ~0ull};
    std::uint64_t v = edges[below(std::size(edges))];
    if (rng() % 2) v = ~v + 1;
    const std::size_t at = below(d.size() - width + 1);
    for (std::size_t i = 0; i < width; ++i) d[at + i] = std::uint8_t(v >> (8 * (rng() % 2 ? i : width - 1 - i)));
  }
  void copy_part(Bytes& d, const Bytes& from) {  // a part of `from` inserted into or written over d
    if (from.empty()) return insert(d);
    const std::size_t src = below(from.size()), n = 1 + below(std::min<std::size_t>(from.size() - src, 64));
    if (rng() % 2 || d.size() < n) {
      const std::size_t at = below(d.size() + 1);
      d.insert(d.begin() + std::ptrdiff_t(at), from.begin() + std::ptrdiff_t(src),
               from.begin() + std::ptrdiff_t(src + n));
    } else {
      const std::size_t at = below(d.size() - n + 1);
      std::copy(from.begin() + std::ptrdiff_t(src), from.begin() + std::ptrdiff_t(src + n),
                d.begin() + std::ptrdiff_t(at));
    }
  }
  void splice(Bytes& d) {  // a prefix of d, then a suffix of another input
    const Bytes& other = corpus[below(corpus.size())];
    const std::size_t keep = below(d.size() + 1), from = below(other.size() + 1);
    d.resize(keep);
    d.insert(d.end(), other.begin() + std::ptrdiff_t(from), other.end());
  }
  void insert_token(Bytes& d) {
    const std::string_view t = tokens()[below(tokens().size())];
    const std::size_t at = below(d.size() + 1);
    d.insert(d.begin() + std::ptrdiff_t(at), t.begin(), t.end());
  }

  void mutate(Bytes& d) {
    const std::size_t n = 1 + below(5);
    for (std::size_t i = 0; i < n; ++i) {
      switch (below(12)) {
        case 0: erase(d); break;
        case 1: insert(d); break;
        case 2: change_byte(d); break;
        case 3: flip_bit(d); break;
        case 4: shuffle(d); break;
        case 5: case 6: ascii_number(d); break;
        case 7: binary_integer(d); break;
        case 8: copy_part(d, d); break;
        case 9: copy_part(d, corpus[below(corpus.size())]); break;
        case 10: splice(d); break;
        default: insert_token(d); break;
      }
      if (d.size() > max_len) d.resize(max_len);
    }
  }
};

std::vector<Bytes> read_corpus(const std::vector<std::string>& dirs, std::size_t max_len) {
  std::vector<std::filesystem::path> files;
  for (const std::string& dir : dirs) {
    std::error_code ec;
    if (std::filesystem::is_regular_file(dir, ec)) {  // one input, as when reproducing a crash
      files.push_back(dir);
      continue;
    }
    for (const auto& e : std::filesystem::directory_iterator(dir, ec))
      if (e.is_regular_file()) files.push_back(e.path());
    if (ec) {
      std::fprintf(stderr, "fuzz_driver: cannot read the corpus directory %s: %s\n", dir.c_str(),
                   ec.message().c_str());
      std::exit(2);
    }
  }
  std::sort(files.begin(), files.end());
  std::vector<Bytes> out;
  for (const auto& f : files) {
    std::ifstream in(f, std::ios::binary);
    Bytes b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (b.size() > max_len) b.resize(max_len);
    out.push_back(std::move(b));
  }
  if (out.empty()) out.emplace_back();  // no seeds: start from the empty input
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  const auto& harnesses = tilekit::fuzz::driver_harnesses();
  auto usage = [&] {
    std::fprintf(stderr,
                 "usage: fuzz_driver NAME [-max_total_time=S] [-runs=N] [-seed=N] [-max_len=B] [-timeout=S] "
                 "[-rss_limit_mb=M] [-artifact_prefix=DIR/] CORPUS_DIR_OR_FILE...\nharnesses:");
    for (const auto& h : harnesses) std::fprintf(stderr, " %s", h.name);
    std::fprintf(stderr, "\n");
    return 2;
  };
  if (argc < 2) return usage();
  const tilekit::fuzz::Harness* harness = nullptr;
  for (const auto& h : harnesses)
    if (argv[1] == std::string_view(h.name)) harness = &h;
  if (!harness) return usage();

  double seconds = 0;
  std::uint64_t runs = 0, seed = 1;
  std::size_t max_len = 16384, rss_limit = 2048;
  int timeout = 10;
  std::vector<std::string> dirs;
  for (int i = 2; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&](const char* flag) -> const char* {
      const std::size_t n = std::strlen(flag);
      return a.compare(0, n, flag) == 0 ? a.c_str() + n : nullptr;
    };
    char* end = nullptr;
    auto number = [&](const char* v) {
      const double x = std::strtod(v, &end);
      if (end == v || *end || x < 0) {
        std::fprintf(stderr, "fuzz_driver: bad value in %s\n", a.c_str());
        std::exit(2);
      }
      return x;
    };
    if (const char* v = value("-max_total_time=")) seconds = number(v);
    else if (const char* v = value("-runs=")) runs = std::uint64_t(number(v));
    else if (const char* v = value("-seed=")) seed = std::uint64_t(number(v));
    else if (const char* v = value("-max_len=")) max_len = std::size_t(number(v));
    else if (const char* v = value("-timeout=")) timeout = int(number(v));
    else if (const char* v = value("-rss_limit_mb=")) rss_limit = std::size_t(number(v));
    else if (const char* v = value("-artifact_prefix=")) std::snprintf(g_prefix, sizeof g_prefix, "%s", v);
    else if (a.rfind("-", 0) == 0) return usage();
    else dirs.push_back(a);
  }

  const std::vector<Bytes> corpus = read_corpus(dirs, max_len);
  install_crash_handlers();
  std::thread(watchdog, timeout, rss_limit).detach();
  std::fprintf(stderr, "fuzz_driver: %s, seed %llu, %zu corpus inputs, %g s, %llu runs (0: no bound)\n", harness->name,
               static_cast<unsigned long long>(seed), corpus.size(), seconds, static_cast<unsigned long long>(runs));

  const auto start = Clock::now();
  std::uint64_t done = 0;
  // libFuzzer hands each input over in a buffer of exactly its size; so does this.
  auto run = [&](const Bytes& in) {
    std::unique_ptr<std::uint8_t[]> copy(new std::uint8_t[std::max<std::size_t>(in.size(), 1)]);
    std::copy(in.begin(), in.end(), copy.get());
    g_data = copy.get();
    g_size = in.size();
    g_started_ms = now_ms();
    harness->run(copy.get(), in.size());
    g_started_ms = -1;
    ++done;
  };
  auto over = [&] {
    if (runs > 0 && done >= runs) return true;
    return seconds > 0 && std::chrono::duration<double>(Clock::now() - start).count() >= seconds;
  };
  for (const Bytes& in : corpus) {
    if (runs > 0 && done >= runs) break;
    run(in);
  }
  Mutator m{std::mt19937_64(seed), corpus, max_len};
  Bytes current;
  if (seconds > 0 || runs > 0) {
    while (!over()) {
      if (current.empty() || m.below(4) != 0) current = corpus[m.below(corpus.size())];
      m.mutate(current);
      run(current);
    }
  }
  const double took = std::chrono::duration<double>(Clock::now() - start).count();
  std::fprintf(stderr, "stat::number_of_executed_units: %llu\n", static_cast<unsigned long long>(done));
  std::fprintf(stderr, "Done %llu runs in %d second(s)\n", static_cast<unsigned long long>(done), int(took));
  return 0;
}
