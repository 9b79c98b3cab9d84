// The shared input layer: files with a size bound, the UTF-8 policy, depth-limited
// JSON with one checked accessor, and the flag parsers every command uses.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "base/error.hpp"
#include "base/input.hpp"
#include "base/json_input.hpp"
#include "base/parallel.hpp"
#include "base/parse.hpp"

using namespace tilekit;

namespace {

template <class F>
std::string message_of(F&& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "no InputError";
}

}  // namespace

TEST(Utf8, AcceptsUtf8AndFindsTheFirstBadByte) {
  EXPECT_EQ(invalid_utf8_offset("plain ASCII"), std::string::npos);
  EXPECT_EQ(invalid_utf8_offset("Gr\xc3\xbc" "nbaum, \xe2\x82\xac, \xf0\x9f\x98\x80"), std::string::npos);
  EXPECT_EQ(invalid_utf8_offset("caf\xe9"), 3u);                 // Latin-1 e-acute
  EXPECT_EQ(invalid_utf8_offset("\xc0\xaf"), 0u);                // overlong '/'
  EXPECT_EQ(invalid_utf8_offset("ab\xed\xa0\x80"), 2u);          // UTF-16 surrogate
  EXPECT_EQ(invalid_utf8_offset("\xf4\x90\x80\x80"), 0u);        // above U+10FFFF
  EXPECT_EQ(invalid_utf8_offset("x\xe2\x82"), 1u);               // truncated
  EXPECT_EQ(utf8_or_question_marks("caf\xe9-\xff"), "caf?-?");
}

TEST(Utf8, RequireUtf8NamesFileLineAndColumn) {
  EXPECT_EQ(message_of([] { require_utf8("0 0 0 0\n# caf\xe9\n", "s.tiles"); }),
            "s.tiles:2: not UTF-8 text (byte 0xe9 at column 6); Tilekit reads UTF-8 only: convert the file (e.g. "
            "`iconv -f latin1 -t utf-8`)");
}

TEST(InputFile, RefusesMissingDirectoriesAndOversizedFiles) {
  EXPECT_EQ(message_of([] { read_input_file("/nonexistent/x.tiles", "tile-set file"); }),
            "/nonexistent/x.tiles: no such tile-set file");
  EXPECT_EQ(message_of([] { read_input_file("/tmp", "checkpoint"); }),
            "/tmp: not a regular file (expected a checkpoint)");
  const std::string path = std::filesystem::temp_directory_path() / ("tk-input-" + std::to_string(getpid()));
  std::ofstream(path) << "0123456789";
  EXPECT_EQ(read_input_file(path, "file"), "0123456789");
  EXPECT_EQ(message_of([&] { read_input_file(path, "file", 9); }),
            path + ": the file is 10 bytes, more than the limit of 9 bytes");
  std::filesystem::remove(path);
}

// Checked on the open file, not by name first: a FIFO (which a plain open would wait on for a
// writer) and a link to an endless device are refused at once.
TEST(InputFile, RefusesAFifoAndALinkToADeviceWithoutBlocking) {
  const std::string dir = std::filesystem::temp_directory_path() / ("tk-input-fifo-" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  ASSERT_EQ(::mkfifo((dir + "/f").c_str(), 0600), 0);
  std::filesystem::create_symlink("/dev/urandom", dir + "/r");
  EXPECT_EQ(message_of([&] { read_input_file(dir + "/f", "attempts file"); }),
            dir + "/f: not a regular file (expected a attempts file)");
  EXPECT_EQ(message_of([&] { read_input_file(dir + "/r", "attempts file"); }),
            dir + "/r: not a regular file (expected a attempts file)");
  std::filesystem::remove_all(dir);
}

TEST(JsonInput, DeepNestingIsRefusedBeforeParsing) {
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_EQ(message_of([&] { parse_json_input(deep, "deep.json"); }),
            "deep.json:1: invalid JSON: nested deeper than 64 levels");
  const std::string ok = std::string(64, '[') + std::string(64, ']');
  EXPECT_NO_THROW(parse_json_input(ok, "ok.json"));
  EXPECT_EQ(json_nesting_depth(R"({"a":"[[[[","b":[{"c":"\"]"}]})", 100), 3);  // brackets in strings do not count
}

TEST(JsonInput, ParserExceptionsBecomeInputErrorsWithoutTheLibraryTag) {
  EXPECT_EQ(message_of([] { parse_json_input(R"({"colors":1e999})", "n.json"); }),
            "n.json: invalid JSON: number overflow parsing '1e999'");
  const std::string bad_utf8 = message_of([] { parse_json_input("{\"name\":\"caf\xe9\"}", "u.json"); });
  EXPECT_EQ(bad_utf8.rfind("u.json: invalid JSON: parse error at line 1", 0), 0u) << bad_utf8;
  EXPECT_EQ(bad_utf8.find("json.exception"), std::string::npos);
}

TEST(JsonIn, EveryTypeAndRangeProblemNamesThePath) {
  const auto doc = nlohmann::json::parse(
      R"({"cells":[[0,1],[2,1e100]],"big":123456789012345678901234567890,"neg":-1,"s":null,"f":2.5,"b":"yes"})");
  const JsonIn j(doc, "t.json");
  EXPECT_EQ(message_of([&] { j.at("cells")[1][1].integer(0, 4294967295); }),
            "t.json: cells[1][1]: expected an integer between 0 and 4294967295, got 1e+100");
  EXPECT_EQ(message_of([&] { j.at("big").integer(); }),
            "t.json: big: expected an integer between -9223372036854775808 and 9223372036854775807, got "
            "1.2345678901234568e+29");
  EXPECT_EQ(message_of([&] { j.at("neg").unsigned_integer(); }),
            "t.json: neg: expected an integer between 0 and 18446744073709551615, got -1");
  EXPECT_EQ(message_of([&] { j.at("rows"); }), "t.json: missing \"rows\"");
  EXPECT_EQ(message_of([&] { j.at("cells").at("x"); }), "t.json: cells: expected a JSON object, got [[0,1],[2,1e+100]]");
  EXPECT_EQ(message_of([&] { j.at("f").integer(); }),
            "t.json: f: expected an integer between -9223372036854775808 and 9223372036854775807, got 2.5");
  EXPECT_EQ(message_of([&] { j.at("b").boolean(); }), "t.json: b: expected true or false, got \"yes\"");
  EXPECT_EQ(message_of([&] { j.at("cells")[0].array(3, 3); }), "t.json: cells[0]: expected an array of 3 elements, got 2");
  EXPECT_FALSE(j.find("s").has_value());  // null reads as absent
  EXPECT_EQ(j.integer_or("s", 7, 0, 10), 7);
  EXPECT_EQ(j.at("cells")[1][0].integer(0, 5), 2);
}

TEST(FlagParsers, IntegersAreStrictAndBounded) {
  EXPECT_EQ(parse_integer("42", 0, 100, "--x"), 42);
  EXPECT_EQ(parse_integer("-3", -5, 5, "--x"), -3);
  for (const char* bad : {"", "+1", " 1", "1 ", "0x10", "1e3", "99999999999999999999", "101"})
    EXPECT_EQ(message_of([&] { parse_integer(bad, 0, 100, "--x"); }),
              fmt::format("--x must be an integer between 0 and 100, got '{}'", bad));
}

TEST(FlagParsers, ShardsAreRefusedInsteadOfWrappingAround) {
  EXPECT_EQ(parse_shard("3/64").index, 3);
  EXPECT_EQ(parse_shard("3/64").count, 64);
  EXPECT_EQ(message_of([] { parse_shard("4294967296/1"); }),
            "`shard` must be I/N with 0 <= I < N <= 1000000, got '4294967296/1'");
  for (const char* bad : {"1/1", "-1/2", "0/0", "0/1000001", "0/1/2", "a/2", "0 /2", "02"})
    EXPECT_NE(message_of([&] { parse_shard(bad); }).find("`shard` must be I/N"), std::string::npos) << bad;
  // By default a RequestError about the field `shard`, which the CLI words as its flag.
  try {
    parse_shard("1/1");
    ADD_FAILURE() << "accepted 1/1";
  } catch (const RequestError& e) {
    EXPECT_EQ(e.field(), "shard");
  }
  // Named without backquotes, a plain InputError.
  EXPECT_THROW(
      try { parse_shard("1/1", "the shard"); } catch (const RequestError&) { FAIL() << "a RequestError"; }, InputError);
}

TEST(FlagParsers, DimensionsHaveBothSidesAndAnAreaBound) {
  const Dimensions d = parse_dimensions("16x9", 100, 1000, "--size WxH");
  EXPECT_EQ(d.first, 16);
  EXPECT_EQ(d.second, 9);
  EXPECT_EQ(parse_dimensions("2X3", 100, 1000, "--size").second, 3);
  EXPECT_EQ(message_of([] { parse_dimensions("16", 100, 1000, "--size WxH"); }),
            "--size WxH: expected two positive integers such as 16x16, got '16'");
  EXPECT_EQ(message_of([] { parse_dimensions("0x5", 100, 1000, "--size WxH"); }),
            "--size WxH: each side must be between 1 and 100, got '0x5'");
  EXPECT_EQ(message_of([] { parse_dimensions("100x100", 100, 1000, "--size WxH"); }),
            "--size WxH: 10000 cells is more than the limit of 1000");
}

TEST(FlagParsers, ThreadCountsHaveAnUpperBound) {
  EXPECT_EQ(checked_thread_count(8), 8);
  EXPECT_EQ(message_of([] { checked_thread_count(100000); }), "`threads` must be between 1 and 4096, got 100000");
  EXPECT_EQ(message_of([] { checked_thread_count(0); }), "`threads` must be between 1 and 4096, got 0");
  EXPECT_THROW(parallel_team(2147483647, [](int) {}), InputError);  // the backstop inside the one parallel helper
}
