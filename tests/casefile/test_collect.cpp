// collect(): which files a command line names.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <system_error>

#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> strings(const std::vector<fs::path>& paths) {
  std::vector<std::string> out;
  for (const auto& p : paths)
    out.push_back(p.string());
  return out;
}

TEST_F(CaseFileTest, CollectSearchesDirectoriesSortsAndDeduplicates) {
  write("a/b/x.json", "{}");
  write("a/y.json", "{}");
  write("a/notes.txt", "");
  write("a/README.md", "");
  write("c.json", "{}");
  write("plain.case", "{}");
  const std::string d = dir_.string();
  const auto got =
      collect({d + "/c.json", d + "/a", d + "/a/y.json", d + "/./a/b/x.json", d + "/plain.case"});
  EXPECT_EQ(strings(got),
            (std::vector<std::string>{d + "/a/b/x.json", d + "/a/y.json", d + "/c.json",
                                      d + "/plain.case"}));  // a file named is taken as it is
}

TEST_F(CaseFileTest, CollectRejectsMissingPaths) {
  const std::string missing = (dir_ / "no_such_dir").string();
  try {
    collect({dir_.string(), missing});
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(missing + ": expected ", 0), 0u) << e.what();
  }
}

TEST_F(CaseFileTest, CollectRejectsTwoCasesWithOneName) {
  write("one/same.json", "{}");
  write("two/same.json", "{}");
  try {
    collect({dir_.string()});
    FAIL() << "no error";
  } catch (const CaseError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("\"same\""), std::string::npos) << msg;
    EXPECT_NE(msg.find((dir_ / "one/same.json").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find((dir_ / "two/same.json").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("expected"), std::string::npos) << msg;
  }
}

TEST_F(CaseFileTest, CollectOfEmptyDirectoryIsEmpty) {
  EXPECT_TRUE(collect({dir_.string()}).empty());
}

// Two links to their own folder made the search exponential (and a loop never ends): each
// folder is searched once, by device and inode.
TEST_F(CaseFileTest, CollectSearchesAFolderReachedByLinksOnce) {
  write("d/x.json", "{}");
  fs::create_directory_symlink(".", dir_ / "d/a");
  fs::create_directory_symlink(".", dir_ / "d/b");
  fs::create_directory_symlink("..", dir_ / "d/up");
  std::vector<std::string> notes;
  const auto got =
      collect({(dir_ / "d").string()}, [&](const std::string& n) { notes.push_back(n); });
  EXPECT_EQ(strings(got), (std::vector<std::string>{(dir_ / "d/x.json").string()}));
  ASSERT_EQ(notes.size(), 3u);
  for (const std::string& n : notes)
    EXPECT_NE(n.find(": a symbolic link to a folder searched already"), std::string::npos) << n;
  EXPECT_EQ(notes[0].rfind("glrefcheck: ignored " + (dir_ / "d").string() + "/", 0), 0u)
      << notes[0];
}

// A FIFO named as a case blocked forever; sockets and devices are no cases either. Found in a
// folder, one is ignored with one line; named outright, it is an error of one line (it used to
// be a note and then "no case matches", two lines that did not say why).
// Issue 45: `run cases --out cases/out` made the next `run cases` read out/results.json as a
// case. A folder below the ones named that glrefcheck marked as its output is passed over; named
// outright, it is searched as any folder.
TEST_F(CaseFileTest, CollectPassesOverGlrefchecksOutputFolders) {
  write("suite/x.json", "{}");
  write("suite/out/.glrefcheck", "glrefcheck output folder\n");
  write("suite/out/results.json", "{}");
  write("suite/out/failures/gap.json", "{}");
  std::vector<std::string> notes;
  const auto note = [&](const std::string& n) { notes.push_back(n); };
  EXPECT_EQ(strings(collect({(dir_ / "suite").string()}, note)),
            (std::vector<std::string>{(dir_ / "suite/x.json").string()}));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0], "glrefcheck: ignored " + (dir_ / "suite/out").string() +
                          ": an output folder of glrefcheck's (it holds .glrefcheck)");
  EXPECT_EQ(collect({(dir_ / "suite/out").string()}, note).size(), 2u);
}

TEST_F(CaseFileTest, CollectIgnoresFifosInFoldersAndRefusesThemNamed) {
  write("d/x.json", "{}");
  ASSERT_EQ(mkfifo((dir_ / "d/pipe.json").c_str(), 0600), 0);
  ASSERT_EQ(mkfifo((dir_ / "named.json").c_str(), 0600), 0);
  ASSERT_EQ(symlink("self.json", (dir_ / "d/self.json").c_str()), 0);
  std::vector<std::string> notes;
  const auto note = [&](const std::string& n) { notes.push_back(n); };
  const auto got = collect({(dir_ / "d").string()}, note);
  EXPECT_EQ(strings(got), (std::vector<std::string>{(dir_ / "d/x.json").string()}));
  ASSERT_EQ(notes.size(), 2u);
  std::sort(notes.begin(), notes.end());  // a folder's order is the file system's
  EXPECT_EQ(notes[0], "glrefcheck: ignored " + (dir_ / "d/pipe.json").string() +
                          ": a FIFO, not a regular file");
  EXPECT_EQ(notes[1], "glrefcheck: ignored " + (dir_ / "d/self.json").string() +
                          ": a symbolic link that cannot be followed (" +
                          std::error_code(ELOOP, std::generic_category()).message() + ")");
  const std::vector<std::pair<std::string, std::string>> named = {
      {(dir_ / "named.json").string(), "a FIFO"}, {"/dev/null", "a character device"}};
  for (const auto& [path, kind] : named) {
    try {
      collect({path}, note);
      FAIL() << "no error for " << path;
    } catch (const CaseError& e) {
      EXPECT_EQ(
          std::string(e.what()),
          path + ": expected a case file or a directory of them, got " + kind + " (not read)");
    }
  }
}

// A tab or a line break in a file name split the lines list and digest print.
TEST_F(CaseFileTest, CollectRefusesCaseNamesWithControlCharacters) {
  write("d/ta\tb.json", "{}");
  try {
    collect({(dir_ / "d").string()}, [](const std::string&) {});
    FAIL() << "no error";
  } catch (const CaseError& e) {
    EXPECT_EQ(std::string(e.what()), (dir_ / "d").string() +
                                         "/ta\\tb.json: name: expected a case name without "
                                         "control characters, got \"ta\\tb\": rename the file");
  }
}

// A name that is not UTF-8 cannot go into results.json: refused before any work, not by the
// JSON library mid-run.
TEST_F(CaseFileTest, CollectRefusesPathsThatAreNotUtf8) {
  write("d/ok.json", "{}");
  write("d/x\xff.json", "{}");
  for (const std::string& arg : {(dir_ / "d").string(), (dir_ / "d/x\xff.json").string()}) {
    try {
      collect({arg}, [](const std::string&) {});
      FAIL() << "no error for " << arg;
    } catch (const CaseError& e) {
      EXPECT_EQ(std::string(e.what()),
                (dir_ / "d").string() +
                    "/x\\xFF.json: expected a path in UTF-8 (case names go into "
                    "JSON), got the byte 0xFF at offset " +
                    std::to_string((dir_ / "d").string().size() + 2));
    }
  }
}

}  // namespace
}  // namespace glrc::casefile::test
