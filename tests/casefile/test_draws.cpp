// The case file's draws (cases/README.md, "draws"): each mistake one line naming its field, and
// a loaded case's triangles the assembly of its draws, written back and read again unchanged.
#include "casefile/write.hpp"
#include "tests/casefile/test_helpers.hpp"

namespace glrc::casefile::test {
namespace {

// Five plain vertices and the given draws.
std::string with_draws(const std::string& draws) {
  return R"({"description": "d", "vertices": [{"clip": [-1, -1, 0, 1]}, {"clip": [1, -1, 0, 1]},
    {"clip": [-1, 1, 0, 1]}, {"clip": [1, 1, 0, 1]}, {"clip": [0, 0, 0, 1]}], "draws": )" +
         draws + "}";
}

TEST_F(CaseFileTest, DrawMistakesNameTheirField) {
  EXPECT_CASE_ERROR(with_draws("[]"), "draws");
  EXPECT_CASE_ERROR(with_draws(R"([{"first": 0, "count": 3}])"), "draws[0].mode");
  EXPECT_CASE_ERROR(with_draws(R"([{"mode": "quads", "count": 3}])"), "draws[0].mode");
  EXPECT_CASE_ERROR(with_draws(R"([{"mode": "triangles", "first": 3, "count": 3}])"),
                    "draws[0].count");
  EXPECT_CASE_ERROR(with_draws(R"([{"mode": "triangles", "first": 5, "count": 1}])"),
                    "draws[0].first");
  EXPECT_CASE_ERROR(with_draws(R"([{"mode": "triangles", "count": 3, "restart": "fixed_index"}])"),
                    "draws[0].restart");
  EXPECT_CASE_ERROR(with_draws(R"([{"mode": "triangles", "indices": [0, 1, 5]}])"),
                    "draws[0].indices[2]");
  EXPECT_CASE_ERROR(
      with_draws(
          R"([{"mode": "triangles", "index_type": "unsigned_byte", "indices": [0, 1, 256]}])"),
      "draws[0].indices[2]");
  EXPECT_CASE_ERROR(with_draws(R"([{"mode": "triangles", "indices": [0, 1, 2], "count": 3}])"),
                    "draws[0].count");
  EXPECT_CASE_ERROR(
      with_draws(R"([{"mode": "triangles", "indices": [0, 1, 2], "restart": "index"}])"),
      "draws[0].restart_index");
  EXPECT_CASE_ERROR(with_draws(R"([{"mode": "triangle_strip", "count": 2}])"), "draws");
  EXPECT_CASE_ERROR(
      R"({"description": "d", "vertices": [{"clip": [0, 0, 0, 1]}, {"clip": [1, 0, 0, 1]},
      {"clip": [0, 1, 0, 1]}], "triangles": [[0, 1, 2]], "draws": [{"mode": "triangles", "count": 3}]})",
      "triangles");
}

TEST_F(CaseFileTest, DrawMessagesSayWhatIsMeant) {
  // "none" is no index type a file may name, so the choices leave it out.
  const std::string type =
      error_of(with_draws(R"([{"mode": "triangles", "index_type": "int", "indices": [0, 1, 2]}])"));
  EXPECT_NE(type.find(R"(expected "unsigned_byte", "unsigned_short" or "unsigned_int", got "int")"),
            std::string::npos)
      << type;
  // An integer beyond 64 bits is not blamed on a decimal point it does not have.
  const std::string huge =
      error_of(with_draws(R"([{"mode": "triangles", "count": 18446744073709551616}])"));
  EXPECT_NE(huge.find("(beyond 64-bit integers)"), std::string::npos) << huge;
  EXPECT_NE(error_of(with_draws(R"([{"mode": "triangles", "count": 3.0}])"))
                .find("written with a decimal point"),
            std::string::npos);
}

TEST_F(CaseFileTest, TheRestartIndexNeedNotBeAVertex) {
  const Case c = load_text(with_draws(
      R"([{"mode": "triangle_fan", "index_type": "unsigned_short", "restart": "index",
           "restart_index": 9, "indices": [4, 0, 1, 9, 4, 2, 3]}])"));
  EXPECT_EQ(c.triangles, (std::vector<std::array<uint32_t, 3>>{{4, 0, 1}, {4, 2, 3}}));
}

TEST_F(CaseFileTest, DrawsAreWrittenAndReadBackUnchanged) {
  const Case c = load_text(with_draws(
      R"([{"mode": "triangle_strip", "first": 0, "count": 4},
          {"mode": "triangles", "index_type": "unsigned_byte", "restart": "fixed_index",
           "indices": [0, 1, 255, 2, 3, 4]},
          {"mode": "triangle_fan", "index_type": "unsigned_int", "indices": [4, 0, 1, 3, 2]}])"));
  ASSERT_EQ(c.draws.size(), 3u);
  EXPECT_EQ(c.triangles.size(), 2u + 1u + 3u);
  const Case back = load_text(to_case_file(c), "back.json");
  EXPECT_EQ(back.draws, c.draws);
  EXPECT_EQ(back.triangles, c.triangles);
}

}  // namespace
}  // namespace glrc::casefile::test
