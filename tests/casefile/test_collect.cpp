// collect(): which files a command line names.
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

}  // namespace
}  // namespace glrc::casefile::test
