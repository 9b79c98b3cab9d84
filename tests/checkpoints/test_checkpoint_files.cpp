// Checkpoint files (checkpoints/checkpoint.hpp): what is written reads back the same, and every
// damaged or foreign file is an InputError naming the problem, never a wrong count. A
// checkpoint replaced by a newer one is replaced whole (atomic write).
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "base/error.hpp"
#include "base/hash.hpp"
#include "checkpoints/checkpoint.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
namespace fs = std::filesystem;

namespace {

// A small but complete state: 10 subproblems, 0, 3 and 9 finished, 5 in flight.
SearchState sample_state() {
  SearchState s;
  s.fingerprint = R"({"solver":1,"mode":"count"})";
  s.subproblem_count = 10;
  s.subproblem_hash = 0x0123456789abcdefull;
  s.finished.assign(10, false);
  s.finished[0] = s.finished[3] = s.finished[9] = true;
  s.finished_each = {{4, 1, 100}, {0, 0, 7}, {8, 2, 250}};
  for (const auto& c : s.finished_each) s.finished_counts += c;
  s.in_flight.push_back({5, {{0, 1}, {3, 2}, {7, 0}}, {2, 1, 40}});
  s.restarts = 0;
  s.restart_nodes = 0;
  s.seconds = 12.5;
  return s;
}

PortfolioState sample_portfolio() {
  PortfolioState p;
  p.fingerprint = "portfolio-fp";
  p.round = 2;
  p.next = 1;
  p.seconds = 3.25;
  PortfolioCandidateState a;
  a.name = "plain";
  a.slices = 3;
  a.nodes = 1000;
  a.seconds = 1.5;
  a.engine = sample_state();
  PortfolioCandidateState b;
  b.name = "t=0,2:pi=1,0";
  b.empty = true;
  b.slices = 1;
  b.nodes = 12;
  b.seconds = 0.01;
  p.candidates = {a, b};
  return p;
}

void expect_same(const SearchState& a, const SearchState& b) {
  EXPECT_EQ(a.fingerprint, b.fingerprint);
  EXPECT_EQ(a.subproblem_count, b.subproblem_count);
  EXPECT_EQ(a.subproblem_hash, b.subproblem_hash);
  EXPECT_EQ(a.finished, b.finished);
  EXPECT_EQ(a.finished_counts, b.finished_counts);
  EXPECT_EQ(a.finished_each, b.finished_each);
  ASSERT_EQ(a.in_flight.size(), b.in_flight.size());
  for (std::size_t i = 0; i < a.in_flight.size(); ++i) {
    EXPECT_EQ(a.in_flight[i].index, b.in_flight[i].index);
    EXPECT_EQ(a.in_flight[i].path, b.in_flight[i].path);
    EXPECT_EQ(a.in_flight[i].counted, b.in_flight[i].counted);
  }
  EXPECT_EQ(a.restarts, b.restarts);
  EXPECT_EQ(a.restart_nodes, b.restart_nodes);
  EXPECT_DOUBLE_EQ(a.seconds, b.seconds);
}

// Expects an InputError whose message holds `fragment`.
template <class F>
void expect_refused(F&& f, const std::string& fragment) {
  try {
    f();
    ADD_FAILURE() << "accepted; expected an InputError saying '" << fragment << "'";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

// `text` with its body replaced and the header resealed (length and checksum right).
std::string resealed_body(const std::string& body) {
  return seal_checkpoint("TILEKIT-CHECKPOINT", kCheckpointVersion, body);
}

std::string body_of(const std::string& text) {
  const auto eol1 = text.find('\n');
  return text.substr(text.find('\n', eol1 + 1) + 1);
}

}  // namespace

TEST(CheckpointFiles, ASearchStateRoundTripsThroughAFile) {
  test::TempDir d;
  const SearchState s = sample_state();
  write_checkpoint(d / "c.ckpt", s);
  expect_same(read_checkpoint(d / "c.ckpt"), s);
  // The text form too, with the header the README documents.
  const std::string text = encode_checkpoint(s);
  EXPECT_EQ(text.rfind(fmt::format("TILEKIT-CHECKPOINT {}\nbytes ", kCheckpointVersion), 0), 0u) << text;
  expect_same(decode_checkpoint(text, "memory"), s);
  EXPECT_EQ(test::slurp(d / "c.ckpt"), text);  // the file holds exactly the encoding
}

TEST(CheckpointFiles, ARequestAndAPortfolioRoundTrip) {
  test::TempDir d;
  CheckpointFile f;
  f.request = {{"kind", "wang"}, {"colors", 2}, {"mode", "first"}};
  f.portfolio = sample_portfolio();
  write_checkpoint(d / "p.ckpt", f);
  const CheckpointFile back = read_checkpoint_file(d / "p.ckpt");
  EXPECT_EQ(back.request, f.request);
  EXPECT_FALSE(back.search.has_value());
  ASSERT_TRUE(back.portfolio.has_value());
  const PortfolioState& p = *back.portfolio;
  EXPECT_EQ(p.fingerprint, "portfolio-fp");
  EXPECT_EQ(p.round, 2u);
  EXPECT_EQ(p.next, 1u);
  EXPECT_DOUBLE_EQ(p.seconds, 3.25);
  ASSERT_EQ(p.candidates.size(), 2u);
  EXPECT_EQ(p.candidates[0].name, "plain");
  EXPECT_EQ(p.candidates[0].nodes, 1000u);
  ASSERT_TRUE(p.candidates[0].engine.has_value());
  expect_same(*p.candidates[0].engine, sample_state());
  EXPECT_EQ(p.candidates[1].name, "t=0,2:pi=1,0");
  EXPECT_TRUE(p.candidates[1].empty);
  EXPECT_FALSE(p.candidates[1].engine.has_value());
  // A portfolio file is not a single search.
  expect_refused([&] { read_checkpoint(d / "p.ckpt"); }, "holds a portfolio, not a single search");
}

TEST(CheckpointFiles, EveryTruncationIsRefused) {
  const std::string text = encode_checkpoint(sample_state());
  // Every cut: inside the magic, the version, the header and the body.
  for (std::size_t len = 0; len < text.size(); len += (len < 64 ? 1 : 17))
    expect_refused([&] { decode_checkpoint(text.substr(0, len), "cut"); }, "checkpoint cut");
  expect_refused([&] { decode_checkpoint(text.substr(0, text.size() - 1), "cut"); }, "truncated");
}

TEST(CheckpointFiles, CorruptedBytesAreRefusedByTheChecksum) {
  const std::string text = encode_checkpoint(sample_state());
  const std::size_t body_start = text.size() - body_of(text).size();
  for (std::size_t at = body_start; at < text.size(); at += 7) {
    std::string bad = text;
    bad[at] = char(bad[at] ^ 0x20);
    expect_refused([&] { decode_checkpoint(bad, "flipped"); }, "checksum mismatch");
  }
  expect_refused([&] { decode_checkpoint(text + "x", "longer"); }, "bytes after the end");
}

TEST(CheckpointFiles, OtherVersionsAreRefusedNamingTheVersion) {
  const std::string body = body_of(encode_checkpoint(sample_state()));
  for (int v : {1, 2, kCheckpointVersion + 1, 99}) {
    const std::string text = seal_checkpoint("TILEKIT-CHECKPOINT", v, body);
    expect_refused([&] { decode_checkpoint(text, "old"); }, fmt::format("format version {} is not supported", v));
  }
  std::string text = encode_checkpoint(sample_state());
  text.replace(text.find(' '), 2, " x");  // not a number
  expect_refused([&] { decode_checkpoint(text, "v"); }, "is not supported");
}

TEST(CheckpointFiles, ForeignFilesAreRefused) {
  test::TempDir d;
  expect_refused([&] { decode_checkpoint("", "empty"); }, "not a Tilekit checkpoint file");
  expect_refused([&] { decode_checkpoint("{\"search\": {}}\n", "json"); }, "not a Tilekit checkpoint file");
  expect_refused([&] { decode_checkpoint("TILEKIT-CHECKPOINTS 3\n", "close"); }, "not a Tilekit checkpoint file");
  // Another Tilekit envelope (same layout, another magic) is not a search checkpoint.
  const std::string other = seal_checkpoint("TILEKIT-OTHER", 1, "{}");
  expect_refused([&] { decode_checkpoint(other, "other"); }, "not a Tilekit checkpoint file");
  // A sealed envelope whose body is not a checkpoint's.
  expect_refused([&] { decode_checkpoint(resealed_body("[1, 2, 3]"), "array"); }, "checkpoint array");
  expect_refused([&] { decode_checkpoint(resealed_body("{\"request\": null}"), "neither"); },
                 "neither or both of a search and a portfolio state");
  expect_refused([&] { decode_checkpoint(resealed_body("not json"), "text"); }, "checkpoint text");
  // A missing file, and a directory, through the path reader.
  expect_refused([&] { read_checkpoint(d / "missing.ckpt"); }, "missing.ckpt");
  expect_refused([&] { read_checkpoint(d.path.string()); }, d.path.string());
}

TEST(CheckpointFiles, AStructurallyWrongStateIsRefusedEvenWithARightChecksum) {
  const std::string body = body_of(encode_checkpoint(sample_state()));
  nlohmann::json j = nlohmann::json::parse(body);
  // An in-flight subproblem that is also finished would be counted twice.
  nlohmann::json twice = j;
  twice["search"]["in_flight"][0]["index"] = 3;
  EXPECT_THROW(decode_checkpoint(resealed_body(twice.dump()), "twice"), InputError);
  // A bitmap shorter than the subproblem count.
  nlohmann::json shortmap = j;
  shortmap["search"]["subproblems"] = 100;
  EXPECT_THROW(decode_checkpoint(resealed_body(shortmap.dump()), "short"), InputError);
  // Finished marks whose counts do not add up to the total.
  nlohmann::json sums = j;
  sums["search"]["finished_each"][0][0] = 5;
  EXPECT_THROW(decode_checkpoint(resealed_body(sums.dump()), "sums"), InputError);
  // The untouched body reads (the three refusals above are about their edits only).
  EXPECT_NO_THROW(decode_checkpoint(resealed_body(body), "same"));
}

TEST(CheckpointFiles, ANewCheckpointReplacesTheOldOneWhole) {
  test::TempDir d;
  const std::string path = d / "c.ckpt";
  SearchState first = sample_state();
  write_checkpoint(path, first);
  SearchState second = sample_state();
  second.finished[5] = true;
  second.in_flight.clear();
  second.finished_each.insert(second.finished_each.begin() + 2, SearchCounters{2, 1, 40});
  second.finished_counts += SearchCounters{2, 1, 40};
  second.seconds = 20;
  write_checkpoint(path, second);
  expect_same(read_checkpoint(path), second);
  for (const auto& e : fs::directory_iterator(d.path)) EXPECT_EQ(e.path().filename(), "c.ckpt");  // no temp file
}

TEST(CheckpointFiles, AWriterKilledMidWayLeavesTheOldCheckpointReadable) {
  test::TempDir d;
  const std::string path = d / "c.ckpt";
  write_checkpoint(path, sample_state());
  // A large state (a long in-flight path) makes each write take a while; kill writers at
  // several moments: the file always reads as a whole checkpoint, the old one or the new one.
  SearchState big = sample_state();
  big.in_flight[0].path.assign(std::size_t(1) << 19, Decision{1, 1});
  for (int delay_us : {1000, 60000, 200000, 500000}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      for (;;) write_checkpoint(path, big);  // killed at some moment of some write
    }
    ::usleep(useconds_t(delay_us));
    ::kill(child, SIGKILL);
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    SearchState now;
    ASSERT_NO_THROW(now = read_checkpoint(path)) << delay_us;
    EXPECT_TRUE(now.in_flight[0].path.size() == 3 || now.in_flight[0].path.size() == big.in_flight[0].path.size());
  }
}
