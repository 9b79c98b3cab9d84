// Inputs and outputs as one policy (base/io_paths.hpp) and user text escaped for its language
// (base/text_escape.hpp).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "base/error.hpp"
#include "base/io_paths.hpp"
#include "base/text_escape.hpp"
#include "tests/cli_runner.hpp"

using namespace tilekit;
namespace fs = std::filesystem;

namespace {

// The message of the InputError check_io_paths throws, or "" when it accepts `paths`.
std::string io_refusal(const std::vector<IoPath>& paths) {
  try {
    check_io_paths(paths);
  } catch (const InputError& e) {
    return e.what();
  }
  return {};
}

}  // namespace

TEST(IoPaths, SameFileSeesLinksHardLinksAndPathsNotYetWritten) {
  test::TempDir d;
  test::write_text(d / "a", "x");
  fs::create_symlink(d / "a", d / "link");
  fs::create_hard_link(d / "a", d / "hard");
  fs::create_directory(d / "sub");
  test::write_text(d / "b", "x");
  EXPECT_TRUE(same_file(d / "a", d / "link"));
  EXPECT_TRUE(same_file(d / "a", d / "hard"));
  EXPECT_TRUE(same_file(d / "a", d / "sub/../a"));
  EXPECT_FALSE(same_file(d / "a", d / "b"));  // equal bytes, another file
  EXPECT_TRUE(same_file(d / "new", d / "sub/../new"));
  EXPECT_FALSE(same_file(d / "new", d / "a"));
  EXPECT_TRUE(inside_folder(d / "sub/x", d.path.string()));
  EXPECT_TRUE(inside_folder(d / "sub/x", d / "sub/"));
  EXPECT_FALSE(inside_folder(d / "subx", d / "sub"));
}

TEST(IoPaths, AnOutputOverAnInputOrAnotherOutputIsRefused) {
  test::TempDir d;
  test::write_text(d / "in", "x");
  EXPECT_NE(io_refusal({{"IN", d / "in", PathRole::Input, {}}, {"out", d / "in", PathRole::Output, {}}})
                .find("out names the same file as IN"),
            std::string::npos);
  EXPECT_NE(io_refusal({{"a", d / "o", PathRole::Output, {}}, {"b", d / "./o", PathRole::Output, {}}})
                .find("a and b name the same file"),
            std::string::npos);
  EXPECT_NE(io_refusal({{"db", d / "in", PathRole::Database, {}}, {"out", d / "in", PathRole::Output, {}}}), "");
  // A checkpoint resumed and written again in its place.
  EXPECT_EQ(
      io_refusal({{"resume", d / "in", PathRole::Input, {}}, {"checkpoint", d / "in", PathRole::Output, "resume"}}),
      "");
  // A file inside an input folder is an input; a folder output holding an input is refused.
  fs::create_directory(d / "tiles");
  test::write_text(d / "tiles/tiles.json", "{}");
  EXPECT_NE(
      io_refusal({{"DIR", d / "tiles", PathRole::Input, {}}, {"out", d / "tiles/tiles.json", PathRole::Output, {}}}),
      "");
  EXPECT_NE(io_refusal(
                {{"ex", d / "tiles/tiles.json", PathRole::Input, {}}, {"out", d / "tiles", PathRole::OutputFolder, {}}})
                .find("holds"),
            std::string::npos);
  EXPECT_EQ(io_refusal({{"ex", d / "in", PathRole::Input, {}}, {"out", d / "tiles", PathRole::OutputFolder, {}}}), "");
  // Nothing was written by any of these.
  EXPECT_EQ(test::slurp(d / "in"), "x");
  EXPECT_FALSE(fs::exists(d / "o"));
}

TEST(IoPaths, AnOutputThatCannotBeWrittenIsRefused) {
  test::TempDir d;
  test::write_text(d / "file", "x");
  fs::create_directory(d / "folder");
  EXPECT_NE(io_refusal({{"out", d / "missing/x", PathRole::Output, {}}}).find("does not exist"), std::string::npos);
  EXPECT_NE(io_refusal({{"out", d / "file/x", PathRole::Output, {}}}).find("is not a folder"), std::string::npos);
  EXPECT_NE(io_refusal({{"out", d / "folder", PathRole::Output, {}}}).find("it is a folder"), std::string::npos);
  EXPECT_NE(io_refusal({{"db", d / "missing/r.sqlite", PathRole::WrittenDatabase, {}}}), "");
  EXPECT_EQ(io_refusal({{"db", d / "missing/r.sqlite", PathRole::Database, {}}}),
            "");  // read only: its reader's to say
  // A folder output is made with its missing parents; a file in its place is refused.
  EXPECT_EQ(io_refusal({{"out", d / "missing/deeper/T", PathRole::OutputFolder, {}}}), "");
  EXPECT_NE(io_refusal({{"out", d / "file", PathRole::OutputFolder, {}}}), "");
  // The databases a refused run removes again: those that do not exist yet.
  test::write_text(d / "old.sqlite", "");
  EXPECT_EQ(databases_to_create({{"db", d / "old.sqlite", PathRole::WrittenDatabase, {}},
                                 {"db", d / "new.sqlite", PathRole::WrittenDatabase, {}},
                                 {"db", d / "read.sqlite", PathRole::Database, {}}}),
            std::vector<std::string>{d / "new.sqlite"});
  test::write_text(d / "new.sqlite", "");
  test::write_text(d / "new.sqlite-journal", "");
  remove_created_files({d / "new.sqlite"});
  EXPECT_FALSE(fs::exists(d / "new.sqlite"));
  EXPECT_FALSE(fs::exists(d / "new.sqlite-journal"));
  EXPECT_TRUE(fs::exists(d / "old.sqlite"));
}

TEST(TextEscape, HtmlAndCommentTextStayText) {
  EXPECT_EQ(html_escape("<img src=x onerror='a(\"1\")'>&"),
            "&lt;img src=x onerror=&#39;a(&quot;1&quot;)&#39;&gt;&amp;");
  EXPECT_EQ(comment_text("a */ b /* c"), "a * / b / * c");
  EXPECT_EQ(comment_text("x\n#error y\r\\"), "x?#error y?/");
  EXPECT_EQ(comment_text("**/"), "** /");
  EXPECT_EQ(comment_text("caf\xc3\xa9"), "caf??");
  EXPECT_EQ(comment_text("plain text (ok) 1.5"), "plain text (ok) 1.5");
}
