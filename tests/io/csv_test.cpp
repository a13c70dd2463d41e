// specula::io CSV input (include/specula/io/csv.h): every syntax rule, every error with its
// exact one-line message, files, column lookup, and the round trip of io::to_csv output.
#include "specula/io/csv.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <rapidcheck/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

#include "specula/exceptions.h"
#include "specula/io/table.h"

namespace specula::io {
namespace {

namespace fs = std::filesystem;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsNan;

constexpr double kInfinite = std::numeric_limits<double>::infinity();

// The message of the InvalidArgument that parse_csv(text, "data.csv") throws ("" if none).
std::string csv_error_of(std::string_view text) {
  try {
    (void)parse_csv(text, "data.csv");
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "";
}

// A file in the temporary directory, removed at the end of the test.
class TempFile {
 public:
  explicit TempFile(std::string_view content)
      : path_(fs::temp_directory_path() /
              fmt::format("specula-csv-test-{}-{}.csv", ::getpid(),
                          ::testing::UnitTest::GetInstance()->current_test_info()->name())) {
    std::ofstream(path_, std::ios::binary) << content;
  }
  ~TempFile() {
    std::error_code ignored;
    fs::remove(path_, ignored);
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// ---- layout ---------------------------------------------------------------------------------

TEST(ParseCsv, HeaderThenColumnMajorValuesWithTheirLines) {
  const auto data = parse_csv("n,coef\n1,0.5\n2,0.25\n10,1e-3\n", "data.csv");
  EXPECT_THAT(data.columns, ElementsAre("n", "coef"));
  ASSERT_EQ(data.values.size(), 2u);
  EXPECT_THAT(data.values[0], ElementsAre(1, 2, 10));
  EXPECT_THAT(data.values[1], ElementsAre(0.5, 0.25, 1e-3));
  EXPECT_THAT(data.lines, ElementsAre(2, 3, 4));
}

TEST(ParseCsv, OneColumnAndNoFinalLineEnding) {
  const auto data = parse_csv("x\n3\n-4", "data.csv");
  EXPECT_THAT(data.columns, ElementsAre("x"));
  EXPECT_THAT(data.values[0], ElementsAre(3, -4));
  EXPECT_THAT(data.lines, ElementsAre(2, 3));
}

TEST(ParseCsv, FieldsAreTrimmedOfSpacesAndTabs) {
  const auto data = parse_csv(" n \t,\tcoef \n  1 ,\t2\t\n", "data.csv");
  EXPECT_THAT(data.columns, ElementsAre("n", "coef"));
  EXPECT_THAT(data.values[0], ElementsAre(1));
  EXPECT_THAT(data.values[1], ElementsAre(2));
}

TEST(ParseCsv, QuotedFieldsKeepCommasSpacesAndDoubledQuotes) {
  const auto data = parse_csv(
      "\"n\", \" a, b \" ,\"say \"\"hi\"\"\",\"\"\"\"\n"
      "\"1\", 2 ,\"3.5\" , \"-4\"\n",
      "data.csv");
  EXPECT_THAT(data.columns, ElementsAre("n", " a, b ", "say \"hi\"", "\""));
  EXPECT_THAT(data.values,
              ElementsAre(ElementsAre(1), ElementsAre(2), ElementsAre(3.5), ElementsAre(-4)));
}

TEST(ParseCsv, LfCrlfAndMixedLineEndings) {
  const std::vector<double> expected{1, 2, 3};
  for (const char* text :
       {"x\n1\n2\n3\n", "x\r\n1\r\n2\r\n3\r\n", "x\r\n1\n2\r\n3", "x\n1\r\n2\n3\r\n"}) {
    SCOPED_TRACE(text);
    const auto data = parse_csv(text, "data.csv");
    EXPECT_THAT(data.columns, ElementsAre("x"));
    EXPECT_EQ(data.values[0], expected);
    EXPECT_THAT(data.lines, ElementsAre(2, 3, 4));
  }
}

TEST(ParseCsv, ByteOrderMarkAtTheStartIsSkipped) {
  const auto data = parse_csv("\xEF\xBB\xBFn,k\r\n1,2\r\n", "data.csv");
  EXPECT_THAT(data.columns, ElementsAre("n", "k"));
  EXPECT_THAT(data.values[0], ElementsAre(1));
  EXPECT_THAT(data.lines, ElementsAre(2));
}

TEST(ParseCsv, BlankLinesAreSkippedButCounted) {
  const auto data = parse_csv("\n  \nn,k\n\n1,2\n \t \r\n\n3,4\n\n", "data.csv");
  EXPECT_THAT(data.columns, ElementsAre("n", "k"));
  EXPECT_THAT(data.values[0], ElementsAre(1, 3));
  EXPECT_THAT(data.lines, ElementsAre(5, 8));
}

TEST(ParseCsv, CommentLinesAreSkippedButCounted) {
  const auto data = parse_csv(
      "# made by make_table.py\n#n,k\nn,k\n# first\n1,2\n  # indented, abc\n3,4\n", "data.csv");
  EXPECT_THAT(data.columns, ElementsAre("n", "k"));
  EXPECT_THAT(data.values[0], ElementsAre(1, 3));
  EXPECT_THAT(data.values[1], ElementsAre(2, 4));
  EXPECT_THAT(data.lines, ElementsAre(5, 7));
}

// ---- numbers --------------------------------------------------------------------------------

TEST(ParseCsv, NumberForms) {
  const auto data = parse_csv("x\n0\n-2.5\n+3\n1e3\n2.5E-2\n.5\n5.\n-0\n4.9e-324\n", "data.csv");
  EXPECT_THAT(data.values[0], ElementsAre(0, -2.5, 3, 1000, 0.025, 0.5, 5, 0, 4.9e-324));
  EXPECT_TRUE(std::signbit(data.values[0][7]));
}

TEST(ParseCsv, NonFiniteValuesAreKeptInAnyCase) {
  const auto data =
      parse_csv("x\nnan\nNaN\nNAN\n+nan\ninf\nInf\n+INF\n-inf\n-Inf\ninfinity\n", "data.csv");
  const auto& x = data.values[0];
  ASSERT_EQ(x.size(), 10u);
  for (std::size_t r = 0; r < 4; ++r) EXPECT_THAT(x[r], IsNan()) << "row " << r;
  EXPECT_THAT(std::vector<double>(x.begin() + 4, x.end()),
              ElementsAre(kInfinite, kInfinite, kInfinite, -kInfinite, -kInfinite, kInfinite));
}

// ---- errors ---------------------------------------------------------------------------------

TEST(ParseCsvError, EmptyFile) {
  for (const char* text :
       {"", "\n\n", " \t\r\n", "\xEF\xBB\xBF", "# only a comment\n\n#another\n"}) {
    SCOPED_TRACE(text);
    EXPECT_EQ(csv_error_of(text), "data.csv: empty file, expected a header line");
  }
}

TEST(ParseCsvError, NoDataRows) {
  EXPECT_EQ(csv_error_of("n,k\n"), "data.csv: no data rows");
  EXPECT_EQ(csv_error_of("n,k"), "data.csv: no data rows");
  EXPECT_EQ(csv_error_of("# x\nn,k\n\n# y\n"), "data.csv: no data rows");
}

TEST(ParseCsvError, EmptyColumnName) {
  EXPECT_EQ(csv_error_of("n,,k\n1,2,3\n"), "data.csv line 1, column 2: empty column name");
  EXPECT_EQ(csv_error_of("\nn, \t\n1,2\n"), "data.csv line 2, column 2: empty column name");
  EXPECT_EQ(csv_error_of("\"\",k\n1,2\n"), "data.csv line 1, column 1: empty column name");
  EXPECT_EQ(csv_error_of("n,k,\n1,2,3\n"), "data.csv line 1, column 3: empty column name");
}

TEST(ParseCsvError, DuplicateColumnName) {
  EXPECT_EQ(csv_error_of("n,k,n\n1,2,3\n"),
            "data.csv line 1, column 3: duplicate column name \"n\" (also column 1)");
  EXPECT_EQ(csv_error_of("# c\na, b ,\"b\"\n1,2,3\n"),
            "data.csv line 2, column 3: duplicate column name \"b\" (also column 2)");
}

TEST(ParseCsvError, TooFewFields) {
  EXPECT_EQ(csv_error_of("n,k,m\n1,2,3\n\n4,5\n"),
            "data.csv line 4, column 3 (\"m\"): too few fields: expected 3, found 2");
  EXPECT_EQ(csv_error_of("n,k\n7\n"),
            "data.csv line 2, column 2 (\"k\"): too few fields: expected 2, found 1");
}

TEST(ParseCsvError, TooManyFields) {
  EXPECT_EQ(csv_error_of("n,k\n1,2\n3,4,5,6\n"),
            "data.csv line 3, column 3: too many fields: expected 2, found 4");
  EXPECT_EQ(csv_error_of("n,k\r\n1,2,\r\n"),
            "data.csv line 2, column 3: too many fields: expected 2, found 3");
}

TEST(ParseCsvError, NotANumber) {
  EXPECT_EQ(csv_error_of("n,k,m\n1,2,3\n\n4,5,abc\n"),
            "data.csv line 4, column 3 (\"m\"): expected a number, got \"abc\"");
  EXPECT_EQ(csv_error_of("n,k\n1,\n"),
            "data.csv line 2, column 2 (\"k\"): expected a number, got \"\"");
  EXPECT_EQ(csv_error_of("n,k\n1, \" 2\"\n"),
            "data.csv line 2, column 2 (\"k\"): expected a number, got \" 2\"");
  EXPECT_EQ(csv_error_of("n\n\"1,5\"\n"),
            "data.csv line 2, column 1 (\"n\"): expected a number, got \"1,5\"");
  for (const std::string bad :
       {"1.5x", "1 2", "0x10", "+-1", "++1", "+", "-", "--1", "e5", "1e", "nanx"}) {
    SCOPED_TRACE(bad);
    EXPECT_EQ(csv_error_of("n\n" + bad + "\n"),
              "data.csv line 2, column 1 (\"n\"): expected a number, got \"" + bad + "\"");
  }
}

TEST(ParseCsvError, NumberOutOfTheRangeOfADouble) {
  EXPECT_EQ(
      csv_error_of("n,k\n1,1e400\n"),
      "data.csv line 2, column 2 (\"k\"): the number \"1e400\" is out of the range of a double");
  EXPECT_EQ(
      csv_error_of("n\n-1e-400\n"),
      "data.csv line 2, column 1 (\"n\"): the number \"-1e-400\" is out of the range of a double");
}

TEST(ParseCsvError, UnterminatedQuote) {
  EXPECT_EQ(csv_error_of("n,\"k\n1,2\n"), "data.csv line 1, column 2: unterminated quote");
  EXPECT_EQ(csv_error_of("n,k\n1,2\n\"3,4\n"), "data.csv line 3, column 1 (\"n\"): unterminated quote");
  EXPECT_EQ(csv_error_of("n,k\n1,\"2\"\"\n"), "data.csv line 2, column 2 (\"k\"): unterminated quote");
}

TEST(ParseCsvError, TextAfterTheClosingQuote) {
  EXPECT_EQ(csv_error_of("\"n\"x,k\n1,2\n"), "data.csv line 1, column 1: text after the closing quote");
  EXPECT_EQ(csv_error_of("n,k\n1,\"2\" 3\n"),
            "data.csv line 2, column 2 (\"k\"): text after the closing quote");
}

TEST(ParseCsvError, ColumnNumbersBeyondTheHeaderAreUnnamed) {
  // The unterminated quote is in column 3 of a two-column file.
  EXPECT_EQ(csv_error_of("n,k\n1,2,\"3\n"), "data.csv line 2, column 3: unterminated quote");
}

TEST(ParseCsvError, SourceNamesTheInput) {
  try {
    (void)parse_csv("n\nx\n", "<stdin>");
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "<stdin> line 2, column 1 (\"n\"): expected a number, got \"x\"");
  }
}

// ---- files ----------------------------------------------------------------------------------

TEST(ReadCsv, ReadsAFile) {
  const TempFile file("\xEF\xBB\xBFn,k\r\n1,2\r\n3,4\r\n");
  const auto data = read_csv(file.path());
  EXPECT_THAT(data.columns, ElementsAre("n", "k"));
  EXPECT_THAT(data.values, ElementsAre(ElementsAre(1, 3), ElementsAre(2, 4)));
  EXPECT_THAT(data.lines, ElementsAre(2, 3));
}

TEST(ReadCsv, ErrorsNameThePath) {
  const TempFile file("n,k\n1,x\n");
  try {
    (void)read_csv(file.path());
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()),
              file.path().string() + " line 2, column 2 (\"k\"): expected a number, got \"x\"");
  }
}

TEST(ReadCsv, MissingFile) {
  const fs::path missing = fs::temp_directory_path() / "specula-csv-test-no-such-file.csv";
  try {
    (void)read_csv(missing);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_EQ(std::string(e.what()),
              "cannot read '" + missing.string() + "': No such file or directory");
  }
}

TEST(ReadCsv, Directory) {
  const fs::path dir = fs::temp_directory_path();
  try {
    (void)read_csv(dir);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_THAT(e.what(), HasSubstr("cannot read '" + dir.string() + "'"));
  }
}

// ---- column_index ---------------------------------------------------------------------------

TEST(ColumnIndex, FindsAColumnByName) {
  const auto data = parse_csv("n,coef,\"a b\"\n1,2,3\n", "data.csv");
  EXPECT_EQ(column_index(data, "n"), 0u);
  EXPECT_EQ(column_index(data, "coef"), 1u);
  EXPECT_EQ(column_index(data, "a b"), 2u);
}

TEST(ColumnIndex, UnknownNameListsTheColumns) {
  const auto data = parse_csv("n,coef,\"a b\"\n1,2,3\n", "data.csv");
  try {
    (void)column_index(data, "N");
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_STREQ(e.what(), "no column \"N\"; the columns are \"n\", \"coef\", \"a b\"");
  }
}

// ---- round trip -----------------------------------------------------------------------------

RC_GTEST_PROP(ParseCsvProperty, ReadsToCsvOutputBackBitIdentically, ()) {
  const auto finite_double =
      rc::gen::suchThat(rc::gen::map(rc::gen::arbitrary<std::uint64_t>(),
                                     [](std::uint64_t b) { return std::bit_cast<double>(b); }),
                        [](double v) { return std::isfinite(v); });
  const auto column_count = *rc::gen::inRange<std::size_t>(1, 6);
  const auto rows = *rc::gen::container<std::vector<std::vector<double>>>(
      *rc::gen::inRange<std::size_t>(1, 20),
      rc::gen::container<std::vector<double>>(column_count, finite_double));
  Table table;
  for (std::size_t c = 0; c < column_count; ++c) table.columns.push_back(fmt::format("c{}", c));
  table.rows = rows;

  const auto data = parse_csv(to_csv(table), "<generated>");
  RC_ASSERT(data.columns == table.columns);
  RC_ASSERT(data.lines.size() == rows.size());
  for (std::size_t r = 0; r < rows.size(); ++r) {
    RC_ASSERT(data.lines[r] == r + 2);
    for (std::size_t c = 0; c < column_count; ++c)
      RC_ASSERT(std::bit_cast<std::uint64_t>(data.values[c][r]) ==
                std::bit_cast<std::uint64_t>(rows[r][c]));
  }
}

}  // namespace
}  // namespace specula::io
