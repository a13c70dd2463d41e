// specula::io tables (include/specula/io/table.h): CSV and JSON text, number formatting and
// rounding (files: files_test.cpp).
#include "specula/io/table.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fmt/format.h>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "specula/exceptions.h"
#include "text_support.h"

namespace specula::io {
namespace {

using ::testing::ElementsAre;
using specula::testing::cells_of;
using specula::testing::lines_of;
using ::testing::HasSubstr;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();



Table sample() {
  Table t;
  t.columns = {"n", "coef"};
  t.rows = {{1, 0.48274947790781993}, {2.5, 0.1}, {1000, 197.49861008019518}};
  t.meta = {{"model", "log"}, {"method", "auto"}};
  return t;
}

// ---- format_number --------------------------------------------------------------------------

TEST(FormatNumber, ShortestRoundTrip) {
  EXPECT_EQ(format_number(0.1), "0.1");
  EXPECT_EQ(format_number(1), "1");
  EXPECT_EQ(format_number(-2.5), "-2.5");
  EXPECT_EQ(format_number(1000), "1000");
  EXPECT_EQ(format_number(0.48274947790781993), "0.4827494779078199");  // 16 digits suffice
  EXPECT_EQ(std::strtod(format_number(1e-300).c_str(), nullptr), 1e-300);
  EXPECT_EQ(std::strtod(format_number(1.0 / 3).c_str(), nullptr), 1.0 / 3);
}

TEST(FormatNumber, FixedDecimals) {
  EXPECT_EQ(format_number(0.48274947790781993, 3), "0.483");
  EXPECT_EQ(format_number(1.6344, 3), "1.634");
  EXPECT_EQ(format_number(2, 2), "2.00");
  EXPECT_EQ(format_number(197.49861008019518, 0), "197");
}

RC_GTEST_PROP(FormatNumberProperty, RoundTripsEveryFiniteDouble, ()) {
  const double x = *rc::gen::suchThat(
      rc::gen::map(rc::gen::arbitrary<std::uint64_t>(), [](std::uint64_t b) { return std::bit_cast<double>(b); }),
      [](double v) { return std::isfinite(v); });
  const std::string text = format_number(x);
  char* end = nullptr;
  const double back = std::strtod(text.c_str(), &end);
  RC_ASSERT(*end == '\0');
  RC_ASSERT(std::bit_cast<std::uint64_t>(back) == std::bit_cast<std::uint64_t>(x));
}

// ---- CSV ------------------------------------------------------------------------------------

TEST(ToCsv, HeaderThenRowsAtFullPrecision) {
  EXPECT_EQ(to_csv(sample()),
            "n,coef\n"
            "1,0.4827494779078199\n"
            "2.5,0.1\n"
            "1000,197.4986100801952\n");
}

TEST(ToCsv, EmptyTableIsTheHeader) {
  Table t;
  t.columns = {"a", "b", "c"};
  EXPECT_EQ(to_csv(t), "a,b,c\n");
}

TEST(ToCsv, NumbersRoundTripExactly) {
  Table t;
  t.columns = {"x"};
  const std::vector<double> xs{1e-300, 0.1, 1.0 / 3, 5e-324, 1.7976931348623157e308, -123.456, 1e21, 2.0 / 3e10};
  for (const double x : xs) t.rows.push_back({x});
  const auto lines = lines_of(to_csv(t));
  ASSERT_EQ(lines.size(), xs.size() + 1);
  for (std::size_t i = 0; i < xs.size(); ++i) {
    SCOPED_TRACE(lines[i + 1]);
    char* end = nullptr;
    EXPECT_EQ(std::strtod(lines[i + 1].c_str(), &end), xs[i]);
    EXPECT_EQ(*end, '\0');
  }
  EXPECT_EQ(lines[1], "1e-300");
  EXPECT_EQ(lines[2], "0.1");
}

TEST(ToCsv, DecimalsRoundAllButTheKeyColumns) {
  Table t;
  t.columns = {"n", "coef", "other"};
  t.rows = {{1.23456, 0.48274947790781993, 2.0}, {0.1, 197.49861008019518, -0.0004}};
  EXPECT_EQ(to_csv(t, 3),
            "n,coef,other\n"
            "1.23456,0.483,2.000\n"
            "0.1,197.499,-0.000\n");

  t.key_columns = 2;
  EXPECT_EQ(to_csv(t, 1),
            "n,coef,other\n"
            "1.23456,0.4827494779078199,2.0\n"
            "0.1,197.4986100801952,-0.0\n");

  t.key_columns = 0;
  EXPECT_EQ(to_csv(t, 2),
            "n,coef,other\n"
            "1.23,0.48,2.00\n"
            "0.10,197.50,-0.00\n");
}

TEST(ToCsv, MetaIsLeftOut) {
  const std::string csv = to_csv(sample());
  EXPECT_THAT(csv, ::testing::Not(HasSubstr("model")));
  EXPECT_THAT(csv, ::testing::Not(HasSubstr("log")));
}

// ---- JSON -----------------------------------------------------------------------------------

TEST(ToJson, MetaFirstThenColumnsThenRowsAsObjects) {
  const std::string text = to_json(sample());
  const auto j = nlohmann::ordered_json::parse(text);
  ASSERT_TRUE(j.is_object());
  std::vector<std::string> keys;
  for (const auto& [key, value] : j.items()) keys.push_back(key);
  EXPECT_THAT(keys, ElementsAre("model", "method", "columns", "rows"));
  EXPECT_EQ(j["model"], "log");
  EXPECT_EQ(j["method"], "auto");
  EXPECT_EQ(j["columns"], nlohmann::ordered_json::array({"n", "coef"}));
  ASSERT_TRUE(j["rows"].is_array());
  ASSERT_EQ(j["rows"].size(), 3u);
  const auto& first = j["rows"][0];
  ASSERT_TRUE(first.is_object());
  std::vector<std::string> row_keys;
  for (const auto& [key, value] : first.items()) row_keys.push_back(key);
  EXPECT_THAT(row_keys, ElementsAre("n", "coef"));
  EXPECT_EQ(first["n"].get<double>(), 1.0);
  EXPECT_EQ(first["coef"].get<double>(), 0.48274947790781993);
  EXPECT_EQ(j["rows"][1]["coef"].get<double>(), 0.1);
  EXPECT_EQ(j["rows"][2]["coef"].get<double>(), 197.49861008019518);
  EXPECT_EQ(text.back(), '\n');
}

TEST(ToJson, EmptyTableHasEmptyRows) {
  Table t;
  t.columns = {"n"};
  const auto j = nlohmann::json::parse(to_json(t));
  EXPECT_TRUE(j["rows"].is_array());
  EXPECT_TRUE(j["rows"].empty());
  EXPECT_EQ(j["columns"], nlohmann::json::array({"n"}));
}

TEST(ToJson, NonFiniteBecomesNull) {
  Table t;
  t.columns = {"n", "a", "b", "c"};
  t.rows = {{1, kNaN, kInf, -kInf}, {kNaN, 2, 3, 4}};
  for (const auto decimals : {std::optional<int>{}, std::optional<int>{3}}) {
    const auto j = nlohmann::json::parse(to_json(t, decimals));
    EXPECT_TRUE(j["rows"][0]["a"].is_null());
    EXPECT_TRUE(j["rows"][0]["b"].is_null());
    EXPECT_TRUE(j["rows"][0]["c"].is_null());
    EXPECT_TRUE(j["rows"][1]["n"].is_null());  // key columns too
    EXPECT_EQ(j["rows"][1]["a"].get<double>(), 2.0);
  }
}

TEST(ToJson, DecimalsRoundAllButTheKeyColumns) {
  Table t;
  t.columns = {"n", "coef", "other"};
  t.rows = {{1.23456, 0.48274947790781993, 197.49861008019518}};
  {
    const auto j = nlohmann::json::parse(to_json(t, 3));
    EXPECT_EQ(j["rows"][0]["n"].get<double>(), 1.23456);
    EXPECT_EQ(j["rows"][0]["coef"].get<double>(), 0.483);
    EXPECT_EQ(j["rows"][0]["other"].get<double>(), 197.499);
  }
  t.key_columns = 2;
  {
    const auto j = nlohmann::json::parse(to_json(t, 1));
    EXPECT_EQ(j["rows"][0]["n"].get<double>(), 1.23456);
    EXPECT_EQ(j["rows"][0]["coef"].get<double>(), 0.48274947790781993);
    EXPECT_EQ(j["rows"][0]["other"].get<double>(), 197.5);
  }
}

TEST(ToJson, SameNumbersAsCsv) {
  Table t = sample();
  t.rows.push_back({1e-300, 1.0 / 3});
  for (const auto decimals : {std::optional<int>{}, std::optional<int>{4}}) {
    const auto csv = lines_of(to_csv(t, decimals));
    const auto j = nlohmann::json::parse(to_json(t, decimals));
    ASSERT_EQ(csv.size(), t.rows.size() + 1);
    ASSERT_EQ(j["rows"].size(), t.rows.size());
    for (std::size_t r = 0; r < t.rows.size(); ++r) {
      const auto cells = cells_of(csv[r + 1]);
      ASSERT_EQ(cells.size(), t.columns.size());
      for (std::size_t c = 0; c < t.columns.size(); ++c)
        EXPECT_EQ(j["rows"][r][t.columns[c]].get<double>(), std::strtod(cells[c].c_str(), nullptr))
            << "row " << r << " column " << t.columns[c];
    }
  }
}

}  // namespace
}  // namespace specula::io
