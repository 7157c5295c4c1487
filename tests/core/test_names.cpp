// core/names.hpp: every enum's table names each enumerator once, and name_of and from_name are
// each other's inverse; the names are the ones users type and files hold.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "core/case.hpp"
#include "core/model.hpp"
#include "core/names.hpp"
#include "core/result.hpp"

namespace glrc {
namespace {

// Every entry round-trips, and no name or value appears twice.
template <class E>
void expect_table_is_a_bijection(size_t enumerators) {
  const auto& table = Names<E>::table;
  EXPECT_EQ(table.size(), enumerators);
  std::set<std::string> names;
  std::set<int> values;
  for (const auto& [value, name] : table) {
    EXPECT_FALSE(name.empty());
    EXPECT_TRUE(names.insert(std::string(name)).second) << name;
    EXPECT_TRUE(values.insert(int(value)).second) << name;
    EXPECT_EQ(name_of(value), name);
    ASSERT_TRUE(from_name<E>(name)) << name;
    EXPECT_EQ(*from_name<E>(name), value);
  }
  EXPECT_EQ(names_of<E>().size(), enumerators);
  EXPECT_FALSE(from_name<E>(""));
  EXPECT_FALSE(from_name<E>("no such name"));
}

TEST(Names, EveryTableIsABijection) {
  expect_table_is_a_bijection<TieBreak>(4);
  expect_table_is_a_bijection<Planes>(2);
  expect_table_is_a_bijection<Interpolation>(3);
  expect_table_is_a_bijection<CullFace>(4);
  expect_table_is_a_bijection<FrontFace>(2);
  expect_table_is_a_bijection<ProvokingVertex>(2);
  expect_table_is_a_bijection<DepthFunc>(8);
  expect_table_is_a_bijection<ToleranceMode>(3);
  expect_table_is_a_bijection<Status>(9);
}

TEST(Names, TheNamesUsersTypeAndFilesHold) {
  EXPECT_STREQ(to_string(TieBreak::bottom_right), "bottom-right");
  EXPECT_STREQ(to_string(Planes::snapped), "snapped");
  EXPECT_STREQ(to_string(Status::expected_fail), "ExpectedFail");
  EXPECT_STREQ(to_string(Status::unexpected_pass), "UnexpectedPass");
  EXPECT_EQ(status_from_string("Timeout"), Status::timeout);
  EXPECT_FALSE(status_from_string("timeout"));  // deqp-runner's names, case and all
  EXPECT_EQ(from_name<CullFace>("front_and_back"), CullFace::front_and_back);
  EXPECT_EQ(choices_text<FrontFace>(), "\"ccw\" or \"cw\"");
  EXPECT_EQ(choices_text<Interpolation>(), "\"smooth\", \"flat\" or \"noperspective\"");
  EXPECT_EQ(Model{}.describe(), "subpixel_bits=8 planes=unsnapped tie=bottom-left");
}

}  // namespace
}  // namespace glrc
