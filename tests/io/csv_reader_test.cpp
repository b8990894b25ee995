// Tests of io/csv_reader.h: table layout detection, column selection, streaming edge cases and
// every error message (file, line, column and the problem).
#include "io/csv_reader.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "common/errors.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

/// Writes `text` to a fresh file and returns its path.
std::string fixture(const std::string& name, const std::string& text) {
  const auto dir = test::make_temp_dir("csv");
  const auto path = dir / name;
  test::write_text(path, text);
  return path.string();
}

using test::error_of;

Series series(const std::string& path, const std::string& column = "", bool drop = false) {
  SeriesReadOptions options;
  options.column = column;
  options.drop_non_finite = drop;
  return read_series(path, options);
}

// --- layout ---------------------------------------------------------------------------------

TEST(TableReader, DetectsCommaWithHeader) {
  TableReader reader(fixture("a.csv", "t,a,b\n0,1,2\n1,3,4\n"));
  EXPECT_EQ(reader.layout().delimiter, Delimiter::kComma);
  EXPECT_THAT(reader.layout().column_names, ElementsAre("t", "a", "b"));
  EXPECT_EQ(reader.layout().header_line, 1);
  EXPECT_EQ(reader.layout().column_count, 3u);
}

TEST(TableReader, DetectsTabSemicolonAndSpaces) {
  EXPECT_EQ(TableReader(fixture("t.tsv", "1\t2\t3\n4\t5\t6\n")).layout().delimiter,
            Delimiter::kTab);
  EXPECT_EQ(TableReader(fixture("s.csv", "a;b\n1;2\n")).layout().delimiter, Delimiter::kSemicolon);
  TableReader spaces(fixture("w.txt", "  1.0   2.0 3.0\n4.0 5.0\t\t6.0  \n"));
  EXPECT_EQ(spaces.layout().delimiter, Delimiter::kWhitespace);
  EXPECT_EQ(spaces.layout().column_count, 3u);
  EXPECT_FALSE(spaces.layout().has_header());
}

TEST(TableReader, ForcedDelimiterWins) {
  // Auto-detection would pick the semicolon; forcing whitespace makes each line one field.
  TableReader reader(fixture("f.txt", "1;2\n3;4\n"), Delimiter::kWhitespace);
  EXPECT_EQ(reader.layout().column_count, 1u);
}

TEST(TableReader, SemicolonPreferredOverDecimalCommas) {
  // European exports: ';' separates, ',' is the decimal mark.
  const auto path = fixture("eu.csv", "a;b\n1,5;2,5\n-0,25;3\n");
  EXPECT_EQ(TableReader(path).layout().delimiter, Delimiter::kSemicolon);
  EXPECT_TRUE(TableReader(path).layout().decimal_comma);
  EXPECT_THAT(series(path, "a").values, ElementsAre(1.5, -0.25));
  EXPECT_THAT(series(path, "b").values, ElementsAre(2.5, 3.0));
  // A field with two commas is no number: refused, located. Among the first (sniffed) lines
  // it means there is no decimal comma, and the first comma field is the error.
  const auto early = fixture("eu2.csv", "a;b\n1,5;2,5\n1,2,3;4\n");
  EXPECT_THAT(error_of([&] { series(early, "a"); }),
              HasSubstr("eu2.csv:2:1: malformed number '1,5' in 'a' (column 1)"));
  std::string text = "a;b\n";
  for (int i = 0; i < 100; ++i) text += "1,5;2,5\n";
  const auto late = fixture("eu3.csv", text + "1,2,3;4\n");
  EXPECT_THAT(error_of([&] { series(late, "a"); }),
              HasSubstr("eu3.csv:102:1: malformed number '1,2,3' in 'a' (column 1)"));
}

TEST(ReadSeries, OneNumberPerLineWithCommentsAndBlanks) {
  const auto s = series(fixture("p.dat", "# header comment\n#\n\n1.5\n  -2e-3 \n\n# mid\n+4\n"));
  EXPECT_THAT(s.values, ElementsAre(1.5, -2e-3, 4.0));
  EXPECT_EQ(s.first_data_line, 4);
  EXPECT_EQ(s.column_name, "column 1");
}

TEST(ReadSeries, CrlfBomAndNoFinalNewline) {
  const auto s = series(fixture("c.csv", "\xEF\xBB\xBFindex,x\r\n0,1.25\r\n1,2.5"), "x");
  EXPECT_THAT(s.values, ElementsAre(1.25, 2.5));
  EXPECT_EQ(s.column_name, "x");
}

TEST(ReadSeries, SelectsByNameThenByOneBasedIndex) {
  const auto path = fixture("n.csv", "a,b,c\n1,2,3\n4,5,6\n");
  EXPECT_THAT(series(path, "b").values, ElementsAre(2.0, 5.0));
  EXPECT_THAT(series(path, "3").values, ElementsAre(3.0, 6.0));
  // Headerless: positional only.
  EXPECT_THAT(series(fixture("h.txt", "1 2\n3 4\n"), "2").values, ElementsAre(2.0, 4.0));
}

TEST(ReadSeries, QuotedFieldsAndQuotedHeader) {
  const auto s = series(fixture("q.csv", "\"t\",\"x\"\n\"0\",\"1.5\"\n"), "x");
  EXPECT_THAT(s.values, ElementsAre(1.5));
}

TEST(ReadSeries, UnrequestedColumnsMayHoldText) {
  const auto s = series(fixture("txt.csv", "x,status\n1,OK\n2,FAIL\n"), "x");
  EXPECT_THAT(s.values, ElementsAre(1.0, 2.0));
}

TEST(ReadSeries, HugeAndTinyExponents) {
  const auto s = series(fixture("e.txt", "1e-400\n1e300\n"));
  EXPECT_EQ(s.values[0], 0.0);
  EXPECT_EQ(s.values[1], 1e300);
  const std::string what = error_of([&] { series(fixture("o.txt", "1\n1e999\n")); });
  EXPECT_THAT(what, HasSubstr("o.txt:2:1: non-finite value '1e999'"));
}

TEST(ReadSeries, LongLinesAreFine) {
  // A 200 000-column row crosses many read blocks' worth of scanning but is legal.
  std::string row;
  for (int i = 0; i < 200000; ++i) {
    if (i > 0) row += ',';
    row += std::to_string(i);
  }
  const auto s = series(fixture("wide.csv", row + "\n" + row + "\n"), "200000");
  EXPECT_THAT(s.values, ElementsAre(199999.0, 199999.0));
}

TEST(ReadSeries, ManyBlocks) {
  // More than one 1 MiB block, with a line straddling the block boundary.
  std::string text = "# x\n";
  for (int i = 0; i < 300000; ++i) text += std::to_string(i) + ".25\n";
  const auto s = series(fixture("big.txt", text));
  ASSERT_EQ(s.values.size(), 300000u);
  EXPECT_EQ(s.values[123456], 123456.25);
  EXPECT_EQ(s.values.back(), 299999.25);
}

// --- errors ---------------------------------------------------------------------------------

TEST(ReadSeriesErrors, MalformedNumberShowsToken) {
  const auto path = fixture("m.csv", "t,x\n0,1\n1,1.2.3\n");
  EXPECT_THAT(error_of([&] { series(path, "x"); }),
              HasSubstr("m.csv:3:3: malformed number '1.2.3' in 'x' (column 2)"));
}

TEST(ReadSeriesErrors, MixedWordsAndNumbersInFirstRowIsDataNotHeader) {
  const auto path = fixture("first.txt", "1.0 abc\n2.0 3.0\n");
  EXPECT_THAT(error_of([&] { series(path, "2"); }),
              HasSubstr("first.txt:1:5: malformed number 'abc' in column 2"));
}

TEST(ReadSeriesErrors, TooFewAndTooManyColumns) {
  const auto few = fixture("few.csv", "a,b,c\n1,2,3\n4,5\n");
  EXPECT_THAT(error_of([&] { series(few, "a"); }),
              HasSubstr("few.csv:3:4: expected 3 columns (as in the header on line 1), found 2"));
  const auto many = fixture("many.txt", "1 2\n3 4 5\n");
  EXPECT_THAT(error_of([&] { series(many, "1"); }),
              HasSubstr("many.txt:2:5: expected 2 columns (as in the first data row on line 1), "
                        "found 3"));
}

TEST(ReadSeriesErrors, EmptyField) {
  EXPECT_THAT(error_of([&] { series(fixture("ef.csv", "a,b\n1,\n"), "b"); }),
              HasSubstr("ef.csv:2:3: empty field in 'b' (column 2)"));
}

TEST(ReadSeriesErrors, UnknownColumnListsAvailable) {
  const auto path = fixture("u.csv", "index,x\n0,1\n");
  EXPECT_THAT(error_of([&] { series(path, "y"); }),
              HasSubstr("u.csv:1: unknown column 'y' (available columns: index, x)"));
  EXPECT_THAT(
      error_of([&] { series(path, "5"); }),
      HasSubstr("column index 5 out of range: the file has 2 column(s), indices start at 1"));
  EXPECT_THAT(error_of([&] { series(fixture("nh.txt", "1 2\n"), "x"); }),
              HasSubstr("nh.txt: unknown column 'x' (available columns: 1..2 (no header row"));
}

TEST(ReadSeriesErrors, SeveralColumnsNeedAChoice) {
  EXPECT_THAT(error_of([&] { series(fixture("two.csv", "index,x\n0,1\n")); }),
              HasSubstr("two.csv:1: the file has 2 columns; choose one by name or 1-based index "
                        "(--column); available columns: index, x"));
}

TEST(ReadSeriesErrors, EmptyCommentOnlyAndHeaderOnly) {
  EXPECT_THAT(error_of([&] { series(fixture("e.txt", "")); }), HasSubstr("e.txt: file is empty"));
  EXPECT_THAT(error_of([&] { series(fixture("c.txt", "# a\n\n  \n#b")); }),
              HasSubstr("c.txt: no data rows (only comments and blank lines)"));
  EXPECT_THAT(error_of([&] { series(fixture("h.csv", "# c\nx\n# c\n")); }),
              HasSubstr("h.csv:2: header row but no data rows"));
}

TEST(ReadSeriesErrors, NonFiniteIsAnErrorUnlessDropped) {
  const auto path = fixture("nan.csv", "t,x\n0,1\n1,NaN\n2,3\n3,-inf\n");
  EXPECT_THAT(error_of([&] { series(path, "x"); }),
              HasSubstr("nan.csv:3:3: non-finite value 'NaN' in 'x' (column 2) (set "
                        "drop_non_finite / --drop-non-finite to drop such rows)"));
  const Series s = series(path, "x", true);
  EXPECT_THAT(s.values, ElementsAre(1.0, 3.0));
  EXPECT_EQ(s.non_finite_dropped, 2);
  EXPECT_THAT(error_of([&] { series(fixture("all.txt", "nan\ninf\n"), "", true); }),
              HasSubstr("all.txt: no data rows left after dropping 2 row(s) holding NaN/Inf"));
}

TEST(ReadSeriesErrors, MissingFileAndDirectory) {
  EXPECT_THAT(error_of([] { series("/nonexistent/dir/rec.csv"); }),
              HasSubstr("/nonexistent/dir/rec.csv: cannot open: No such file or directory"));
  const auto dir = test::make_temp_dir("csvdir");
  EXPECT_THAT(error_of([&] { series(dir.string()); }), HasSubstr("is a directory"));
}

TEST(ReadSeriesErrors, BinaryGarbage) {
  std::string garbage = "1.0\n2.0\nab";
  garbage += std::string("\0\x01\xff\xfe", 4);
  EXPECT_THAT(error_of([&] { series(fixture("bin.dat", garbage)); }),
              HasSubstr("bin.dat:3:3: binary data (NUL byte): not a text table"));
  // High bytes without NUL: a malformed token, printed escaped and bounded.
  EXPECT_THAT(error_of([&] { series(fixture("hi.dat", "1\n\x80\x81\xfe\n")); }),
              HasSubstr("hi.dat:2:1: malformed number '\\x80\\x81\\xFE'"));
  EXPECT_THAT(error_of([&] {
                series(fixture("u16.txt", std::string("\xFF\xFE"
                                                      "1\0",
                                                      4)));
              }),
              HasSubstr("u16.txt:1:1: text is UTF-16 encoded"));
}

TEST(ReadSeriesErrors, OverlongLineIsRefused) {
  const auto path = fixture("long.txt", "1\n" + std::string(17u << 20, '7') + "\n");
  EXPECT_THAT(error_of([&] { series(path); }),
              HasSubstr("long.txt:2: line longer than 16 MiB: not a numeric text table"));
}

TEST(ReadSeriesErrors, LongMalformedTokenIsTruncated) {
  const std::string what =
      error_of([&] { series(fixture("lt.txt", "1\n" + std::string(500, 'x') + "\n")); });
  EXPECT_THAT(what, HasSubstr("lt.txt:2:1: malformed number 'xxxxxxxxxx"));
  EXPECT_THAT(what, HasSubstr("...'"));
  EXPECT_LT(what.size(), 200u);
}

TEST(ReadSeriesErrors, RandomMutationsOnlyEverThrowInputError) {
  // Fixed-seed mutation fuzzing: flipped bytes, cut files, stray separators. Any outcome but
  // a value or an InputError (a crash, another exception, a hang) fails the test.
  const std::string base =
      "# comment\ntime_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s\r\n"
      "0.00,1e-3,-2.5e-4,+3\n0.01,nan,4,5\n\n0.02,1,2,3";
  std::string alphabet = "0123456789eE+-.,;\t #\r\nnaif\"\xff";
  alphabet.push_back('\0');
  std::mt19937 rng(2024);
  const auto dir = test::make_temp_dir("fuzz");
  int outcomes = 0;
  for (int iteration = 0; iteration < 400; ++iteration) {
    std::string text = base;
    const int edits = 1 + static_cast<int>(rng() % 6);
    for (int e = 0; e < edits && !text.empty(); ++e) {
      const std::size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0:
          text[at] = alphabet[rng() % alphabet.size()];
          break;
        case 1:
          text.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
        default:
          text.resize(at);
          break;
      }
    }
    std::string name = std::to_string(iteration);
    name += ".csv";
    const auto path = (dir / name).string();
    test::write_text(path, text);
    for (const char* column : {"", "2", "gyro_y_rad_per_s"}) {
      try {
        SeriesReadOptions options;
        options.column = column;
        options.drop_non_finite = (iteration % 2) == 0;
        (void)read_series(path, options);
      } catch (const InputError&) {
      }
      ++outcomes;
    }
    try {
      (void)read_recording(path, {});
    } catch (const InputError&) {
    }
    ++outcomes;
  }
  EXPECT_EQ(outcomes, 1600);
}

// --- line map ---------------------------------------------------------------------------------

TEST(LineMap, MapsRowsAcrossSkippedLines) {
  LineMap map;
  map.add(0, 3);
  map.add(1, 4);
  map.add(2, 7);  // two lines skipped
  map.add(3, 8);
  EXPECT_EQ(map.line_of(0), 3);
  EXPECT_EQ(map.line_of(1), 4);
  EXPECT_EQ(map.line_of(2), 7);
  EXPECT_EQ(map.line_of(3), 8);
}

TEST(TableReader, RelativeIntegerColumnKeepsNanosecondPrecision) {
  // 1.4e18 ns is beyond 2^53: parsed as doubles these steps of 1 ns would vanish.
  TableReader reader(
      fixture("ns.csv", "1403636579758555392,1\n1403636579758555393,2\n1403636579763555393,3\n"));
  const ColumnRequest requests[] = {{0, true}, {1, false}};
  const TableData data = reader.read(requests, false);
  EXPECT_THAT(data.columns[0], ElementsAre(0.0, 1.0, 5000001.0));
  EXPECT_DOUBLE_EQ(data.first_values[0], 1403636579758555392.0);
  EXPECT_THAT(data.columns[1], ElementsAre(1.0, 2.0, 3.0));
}

// Requests TableReader::read documents as the caller's to avoid are contract violations, not
// input errors: a second read, an index past the columns, one column both relative and not.
TEST(TableReader, CallerBugsAreContractViolations) {
  const std::string path = fixture("contract.csv", "1,2\n3,4\n");
  const ColumnRequest first[] = {{0, false}};
  TableReader twice(path);
  EXPECT_EQ(twice.read(first, false).columns[0].size(), 2u);
  test::expect_throw_containing<ContractViolation>([&] { twice.read(first, false); },
                                                   "TableReader::read called twice");
  const ColumnRequest beyond[] = {{2, false}};
  test::expect_throw_containing<ContractViolation>([&] { TableReader(path).read(beyond, false); },
                                                   "TableReader::read: column index");
  const ColumnRequest mixed[] = {{0, true}, {0, false}};
  test::expect_throw_containing<ContractViolation>(
      [&] { TableReader(path).read(mixed, false); },
      "TableReader::read: column requested both relative and not");
}

}  // namespace
}  // namespace imunoise::io
