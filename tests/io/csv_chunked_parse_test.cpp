// Tests of the memory-mapped, chunked, multi-threaded path of io/csv_reader.h
// (io/csv_chunked_parse): for any chunk size and thread count it must give exactly what the
// streamed sequential path gives (values bit for bit, line map, drop counts, first row) and the
// same first error in file order.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include "common/errors.h"
#include "io/csv_reader.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;

/// Writes `text` to a fresh file and returns its path.
std::string fixture(const std::string& name, const std::string& text) {
  const auto path = test::make_temp_dir("csvpar") / name;
  test::write_text(path, text);
  return path.string();
}

/// The streamed path, whatever the file size.
constexpr ReadParallelism kStreamed{.min_mapped_bytes = std::numeric_limits<std::size_t>::max()};

/// The mapped path on THREADS threads with chunks of CHUNK_BYTES, whatever the file size.
ReadParallelism mapped(unsigned threads, std::size_t chunk_bytes) {
  return {.threads = threads, .min_mapped_bytes = 0, .chunk_bytes = chunk_bytes};
}

/// A read's result, or its InputError message.
using Outcome = std::variant<TableData, std::string>;

Outcome read_table(const std::string& path, std::span<const ColumnRequest> requests, bool drop,
                   const ReadParallelism& parallelism) {
  try {
    TableReader reader(path);
    return reader.read(requests, drop, {}, parallelism);
  } catch (const InputError& e) {
    return std::string(e.what());
  }
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}

/// Every field of two outcomes equal, doubles bit for bit (so −0 ≠ +0).
void expect_same(const Outcome& expected, const Outcome& actual, const std::string& where) {
  SCOPED_TRACE(where);
  ASSERT_EQ(expected.index(), actual.index())
      << (expected.index() == 1 ? "expected error: " + std::get<1>(expected)
                                : "unexpected error: " + std::get<1>(actual));
  if (expected.index() == 1) {
    EXPECT_EQ(std::get<1>(expected), std::get<1>(actual));
    return;
  }
  const TableData& e = std::get<0>(expected);
  const TableData& a = std::get<0>(actual);
  ASSERT_EQ(e.columns.size(), a.columns.size());
  for (std::size_t c = 0; c < e.columns.size(); ++c) {
    EXPECT_EQ(e.columns[c].size(), a.columns[c].size()) << "column " << c;
    EXPECT_TRUE(same_bits(e.columns[c], a.columns[c])) << "column " << c;
  }
  EXPECT_TRUE(same_bits(e.first_values, a.first_values));
  EXPECT_EQ(e.non_finite_dropped, a.non_finite_dropped);
  EXPECT_EQ(e.rows_dropped, a.rows_dropped);
  EXPECT_EQ(e.first_data_line, a.first_data_line);
  EXPECT_TRUE(e.lines == a.lines);
  if (!e.columns.empty()) {
    for (std::size_t r = 0; r < e.columns[0].size(); r += 97) {
      EXPECT_EQ(e.lines.line_of(r), a.lines.line_of(r)) << "row " << r;
    }
  }
}

/// Reads PATH streamed, then mapped under every chunk size and thread count, and expects the
/// same outcome each time. Returns the streamed outcome.
Outcome expect_all_paths_agree(const std::string& path, std::span<const ColumnRequest> requests,
                               bool drop) {
  const Outcome streamed = read_table(path, requests, drop, kStreamed);
  // 1 and 64 bytes: a chunk per line or so; 1 KiB: many lines per chunk; 1 MiB: one chunk.
  for (const std::size_t chunk :
       {std::size_t{1}, std::size_t{64}, std::size_t{1024}, std::size_t{1} << 20}) {
    for (const unsigned threads : {1u, 2u, 3u, 8u}) {
      expect_same(
          streamed, read_table(path, requests, drop, mapped(threads, chunk)),
          "chunk " + std::to_string(chunk) + " B, " + std::to_string(threads) + " thread(s)");
    }
  }
  return streamed;
}

/// How a generated table looks.
struct TableShape {
  int rows = 3000;
  bool header = true;
  bool crlf = false;
  bool comments_and_blanks = false;  // '#' lines and blank lines between data rows
  bool final_newline = true;
  char separator = ',';          // ' ' for whitespace-separated
  bool nanosecond_time = false;  // integer ns stamps near 1.7e18 instead of seconds
  int non_finite_every = 0;      // a NaN/Inf field every N rows (0: none)
};

/// A 7-column table like `imunoise simulate` writes (time + six doubles with up to 17
/// significant digits, so both number parsers are used), fixed seed.
std::string make_table(const TableShape& shape) {
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1e-3);
  const std::string eol = shape.crlf ? "\r\n" : "\n";
  const char sep = shape.separator;
  std::string text;
  if (shape.header) {
    text += "time,gx,gy,gz,ax,ay,az";
    if (sep != ',') {
      for (char& c : text) c = c == ',' ? sep : c;
    }
    text += eol;
  }
  char buffer[64];
  for (int i = 0; i < shape.rows; ++i) {
    if (shape.comments_and_blanks && i % 37 == 5) text += "# comment " + std::to_string(i) + eol;
    if (shape.comments_and_blanks && i % 53 == 11) text += (i % 2 == 0 ? "" : "  \t") + eol;
    if (shape.nanosecond_time) {
      text += std::to_string(std::int64_t{1'700'000'000'123'456'789} + std::int64_t{i} * 2'500'001);
    } else {
      std::snprintf(buffer, sizeof buffer, "%.9f", 1000.0 + 0.0025 * i);
      text += buffer;
    }
    for (int c = 0; c < 6; ++c) {
      text += sep;
      if (shape.non_finite_every > 0 && i % shape.non_finite_every == 3 && c == i % 6) {
        text += (i % 2 == 0) ? "nan" : "-inf";
        continue;
      }
      // Alternate short (fast decimal path) and 17-digit (from_chars) numbers.
      std::snprintf(buffer, sizeof buffer, (i + c) % 3 == 0 ? "%.6f" : "%.17g",
                    (c < 3 ? 0.0 : 9.8) + noise(rng));
      text += buffer;
    }
    if (shape.final_newline || i + 1 < shape.rows) text += eol;
  }
  return text;
}

std::vector<ColumnRequest> all_columns_time_relative() {
  std::vector<ColumnRequest> requests{{0, true}};
  for (std::size_t c = 1; c < 7; ++c) requests.push_back({c, false});
  return requests;
}

// --- identical results ----------------------------------------------------------------------

TEST(CsvParallel, PlainCsvMatchesSequentialForAnyChunkingAndThreads) {
  const auto path = fixture("plain.csv", make_table({}));
  const Outcome out = expect_all_paths_agree(path, all_columns_time_relative(), false);
  ASSERT_EQ(out.index(), 0u) << std::get<1>(out);
  EXPECT_EQ(std::get<0>(out).columns[0].size(), 3000u);
}

TEST(CsvParallel, CrlfCommentsAndBlankLinesInsideTheData) {
  const auto path = fixture("crlf.csv", make_table({.crlf = true, .comments_and_blanks = true}));
  const Outcome out = expect_all_paths_agree(path, all_columns_time_relative(), false);
  ASSERT_EQ(out.index(), 0u) << std::get<1>(out);
  // The line map knows the skipped lines: row 200 is not on line 202.
  EXPECT_GT(std::get<0>(out).lines.line_of(200), 202);
}

TEST(CsvParallel, NoFinalNewlineWhitespaceHeaderless) {
  const auto path = fixture("ws.txt", make_table({.header = false,
                                                  .comments_and_blanks = true,
                                                  .final_newline = false,
                                                  .separator = ' '}));
  const Outcome out = expect_all_paths_agree(path, all_columns_time_relative(), false);
  ASSERT_EQ(out.index(), 0u) << std::get<1>(out);
  EXPECT_EQ(std::get<0>(out).columns[0].size(), 3000u);
}

TEST(CsvParallel, SomeColumnsOnlyAndOneRequestedTwice) {
  const auto path = fixture("some.csv", make_table({.separator = ';'}));
  const std::vector<ColumnRequest> requests{{3, false}, {0, true}, {3, false}};
  expect_all_paths_agree(path, requests, false);
}

TEST(CsvParallel, ChunkBoundaryExactlyAtANewline) {
  // Equal-length lines: every chunk of a multiple of the line length ends exactly on a '\n'.
  std::string text = "a,b\n";
  for (int i = 0; i < 2000; ++i) {
    char line[32];
    std::snprintf(line, sizeof line, "%06d,%06d\n", i, 2 * i);  // 14 bytes
    text += line;
  }
  const auto path = fixture("aligned.csv", text);
  const ColumnRequest requests[] = {{0, false}, {1, false}};
  const Outcome streamed = read_table(path, requests, false, kStreamed);
  ASSERT_EQ(streamed.index(), 0u);
  for (const std::size_t chunk : {13u, 14u, 15u, 28u, 140u}) {
    for (const unsigned threads : {1u, 2u, 3u}) {
      expect_same(streamed, read_table(path, requests, false, mapped(threads, chunk)),
                  "chunk " + std::to_string(chunk));
    }
  }
  EXPECT_EQ(std::get<0>(streamed).columns[1].back(), 3998.0);
}

TEST(CsvParallel, NanosecondStampsStayExactInEveryChunk) {
  const auto path = fixture("ns.csv", make_table({.nanosecond_time = true}));
  const Outcome out = expect_all_paths_agree(path, all_columns_time_relative(), false);
  ASSERT_EQ(out.index(), 0u) << std::get<1>(out);
  const TableData& data = std::get<0>(out);
  // 1.7e18 is far beyond 2^53: only integer subtraction keeps the 2 500 001 ns steps.
  for (std::size_t i = 0; i < data.columns[0].size(); ++i) {
    ASSERT_EQ(data.columns[0][i], static_cast<double>(i) * 2'500'001.0) << "row " << i;
  }
  EXPECT_EQ(data.first_values[0], 1'700'000'000'123'456'789.0);
}

TEST(CsvParallel, NonFiniteRowsDroppedAndCountedAlike) {
  const auto path =
      fixture("nan.csv", make_table({.comments_and_blanks = true, .non_finite_every = 41}));
  const auto requests = all_columns_time_relative();
  const Outcome dropped = expect_all_paths_agree(path, requests, true);
  ASSERT_EQ(dropped.index(), 0u) << std::get<1>(dropped);
  EXPECT_EQ(std::get<0>(dropped).rows_dropped, 74);  // rows 3, 44, 85, … below 3000
  EXPECT_EQ(std::get<0>(dropped).non_finite_dropped, 74);
  // Kept: the first NaN is the reported error, whichever thread parses its chunk.
  const Outcome refused = expect_all_paths_agree(path, requests, false);
  ASSERT_EQ(refused.index(), 1u);
  EXPECT_THAT(std::get<1>(refused), HasSubstr("nan.csv:5:"));
  EXPECT_THAT(std::get<1>(refused), HasSubstr("non-finite value '-inf'"));
}

TEST(CsvParallel, FirstKeptRowAfterDroppedRowsIsTheOrigin) {
  // Rows before the first kept one are dropped: relative columns start from the third row.
  std::string text = "t,x\n# c\n1,nan\n2,inf\n";
  for (int i = 3; i < 400; ++i) text += std::to_string(i) + "," + std::to_string(i) + ".5\n";
  const auto path = fixture("origin.csv", text);
  const ColumnRequest requests[] = {{0, true}, {1, false}};
  const Outcome out = expect_all_paths_agree(path, requests, true);
  ASSERT_EQ(out.index(), 0u) << std::get<1>(out);
  EXPECT_EQ(std::get<0>(out).first_data_line, 5);
  EXPECT_EQ(std::get<0>(out).first_values[0], 3.0);
  EXPECT_EQ(std::get<0>(out).columns[0][1], 1.0);
}

// --- errors ---------------------------------------------------------------------------------

/// The 7-column table with line LINE (1-based; the header is line 1) replaced.
std::string with_line(std::string text, int line, const std::string& replacement) {
  std::size_t begin = 0;
  for (int l = 1; l < line; ++l) begin = text.find('\n', begin) + 1;
  const std::size_t end = text.find('\n', begin);
  return text.replace(begin, end - begin, replacement);
}

TEST(CsvParallel, EarlierErrorWinsOverALaterChunksError) {
  const std::string table = make_table({});
  const auto requests = all_columns_time_relative();
  // Wrong column count early, malformed number late; then the other way round.
  const std::string early_count = with_line(with_line(table, 2900, "1,2,3,x,5,6,7"), 700, "1,2");
  const auto a = fixture("a.csv", early_count);
  const Outcome out_a = expect_all_paths_agree(a, requests, false);
  ASSERT_EQ(out_a.index(), 1u);
  EXPECT_THAT(std::get<1>(out_a),
              HasSubstr("a.csv:700:4: expected 7 columns (as in the header on line 1), found 2"));

  const std::string early_number =
      with_line(with_line(table, 2950, "1,2,3"), 1200, "1,2,3,4.5.6,5,6,7");
  const auto b = fixture("b.csv", early_number);
  const Outcome out_b = expect_all_paths_agree(b, requests, false);
  ASSERT_EQ(out_b.index(), 1u);
  EXPECT_THAT(std::get<1>(out_b), HasSubstr("b.csv:1200:7: malformed number '4.5.6' in 'gz' "
                                            "(column 4)"));
}

TEST(CsvParallel, ErrorsInTheLastLineAndInTheFirstDataRow) {
  const std::string table = make_table({.rows = 500});
  const auto requests = all_columns_time_relative();
  const Outcome last = expect_all_paths_agree(
      fixture("last.csv", with_line(table, 501, "1,2,3,4,5,6,")), requests, false);
  ASSERT_EQ(last.index(), 1u);
  EXPECT_THAT(std::get<1>(last), HasSubstr("last.csv:501:13: empty field in 'az' (column 7)"));
  const Outcome first = expect_all_paths_agree(
      fixture("first.csv", with_line(table, 2, "1,2,3,4,5,6,7,8")), requests, false);
  ASSERT_EQ(first.index(), 1u);
  EXPECT_THAT(std::get<1>(first), HasSubstr("first.csv:2:15: expected 7 columns"));
}

TEST(CsvParallel, HeaderOnlyAndAllRowsDroppedAreErrors) {
  const ColumnRequest requests[] = {{0, false}};
  const Outcome header_only =
      expect_all_paths_agree(fixture("h.csv", "# c\nx,y\n# c\n\n"), requests, false);
  ASSERT_EQ(header_only.index(), 1u);
  EXPECT_THAT(std::get<1>(header_only), HasSubstr("h.csv:2: header row but no data rows"));
  const ColumnRequest both[] = {{0, false}, {1, false}};
  const Outcome all_dropped =
      expect_all_paths_agree(fixture("d.csv", "x,y\nnan,1\n1,inf\n"), both, true);
  ASSERT_EQ(all_dropped.index(), 1u);
  EXPECT_THAT(std::get<1>(all_dropped), HasSubstr("d.csv: no data rows left after dropping 2"));
}

// --- number text ----------------------------------------------------------------------------

TEST(CsvParallel, DigitHeavyNumbersAreCorrectlyRounded) {
  // Shortest round-trip text (what `imunoise simulate` writes: up to 17 significant digits),
  // 19- and 20-digit forms, leading zeros and exponents: every token must give strtod's value.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-32, 32);
  std::string text;
  std::vector<std::string> tokens;
  char buffer[64];
  for (int i = 0; i < 20000; ++i) {
    const double v = mantissa(rng) * std::pow(10.0, exponent(rng));
    switch (i % 4) {
      case 0:
        *std::to_chars(buffer, buffer + sizeof buffer, v).ptr = '\0';
        break;
      case 1:
        std::snprintf(buffer, sizeof buffer, "%.19g", v);
        break;
      case 2:
        std::snprintf(buffer, sizeof buffer, "%.20f", v / 1e6);
        break;
      default:
        std::snprintf(buffer, sizeof buffer, "%.18e", v);
        break;
    }
    tokens.emplace_back(buffer);
    text += tokens.back() + "\n";
  }
  const auto path = fixture("digits.txt", text);
  const ColumnRequest requests[] = {{0, false}};
  const Outcome out = expect_all_paths_agree(path, requests, false);
  ASSERT_EQ(out.index(), 0u) << std::get<1>(out);
  const std::vector<double>& values = std::get<0>(out).columns[0];
  ASSERT_EQ(values.size(), tokens.size());
  for (std::size_t i = 0; i < tokens.size(); ++i) {
    const double expected = std::strtod(tokens[i].c_str(), nullptr);
    ASSERT_EQ(std::memcmp(&values[i], &expected, sizeof expected), 0)
        << tokens[i] << " read as " << values[i];
  }
}

// --- progress and the entry points ----------------------------------------------------------

TEST(CsvParallel, ProgressIsMonotoneFromTheCallingThreadAndEndsAtTheSize) {
  const std::string text = make_table({});
  const auto path = fixture("progress.csv", text);
  const auto requests = all_columns_time_relative();
  const auto caller = std::this_thread::get_id();
  for (const unsigned threads : {1u, 4u}) {
    SCOPED_TRACE(std::to_string(threads) + " thread(s)");
    std::vector<std::int64_t> done_seen;
    bool other_thread = false;
    TableReader reader(path);
    const TableData data = reader.read(
        requests, false,
        [&](std::string_view stage, std::int64_t done, std::int64_t total) {
          other_thread = other_thread || std::this_thread::get_id() != caller;
          EXPECT_EQ(stage, "reading");
          EXPECT_EQ(total, static_cast<std::int64_t>(text.size()));
          done_seen.push_back(done);
        },
        mapped(threads, 4096));
    EXPECT_FALSE(other_thread);
    // The caller reports after each chunk it parses; alone, it parses all ~60 of them.
    ASSERT_GE(done_seen.size(), threads == 1 ? 10u : 1u);
    EXPECT_TRUE(std::is_sorted(done_seen.begin(), done_seen.end()));
    EXPECT_EQ(done_seen.back(), static_cast<std::int64_t>(text.size()));
    EXPECT_EQ(data.columns[0].size(), 3000u);
  }
}

TEST(CsvParallel, AFileThatShrinksWhileItIsReadIsAnErrorNotACrash) {
  // The mapped path reads through a mapping of the file: after another process truncates it,
  // a page past the new end used to raise SIGBUS and kill the process. Truncate the file from
  // the progress callback, after the first chunk, and expect a clear error naming the file.
  const std::string text = make_table({.rows = 20000});
  const auto requests = all_columns_time_relative();
  for (const unsigned threads : {1u, 2u}) {
    SCOPED_TRACE(std::to_string(threads) + " thread(s)");
    const auto path = fixture("shrinks.csv", text);
    bool truncated = false;
    const auto truncate_once = [&](std::string_view, std::int64_t, std::int64_t) {
      if (truncated) return;
      truncated = true;
      std::filesystem::resize_file(path, text.size() / 3);
    };
    try {
      TableReader reader(path);
      (void)reader.read(requests, false, truncate_once, mapped(threads, 16384));
      ADD_FAILURE() << "no error for a file that shrank while it was read";
    } catch (const InputError& e) {
      EXPECT_THAT(e.what(), HasSubstr(path));
      EXPECT_THAT(e.what(), HasSubstr("the file shrank while it was read (it had " +
                                      std::to_string(text.size()) + " bytes when opened)"));
    }
    EXPECT_TRUE(truncated);
  }
}

TEST(CsvParallel, ReadRecordingAndSeriesDoNotDependOnThreads) {
  // Beyond the 4 MiB threshold, so the default parallelism maps the file.
  std::string text =
      "time_s,gyro_x_rad_per_s,gyro_y_rad_per_s,gyro_z_rad_per_s,accel_x_m_per_s2,"
      "accel_y_m_per_s2,accel_z_m_per_s2\n";
  const std::string body = make_table({.rows = 40000, .header = false});
  text += body;
  ASSERT_GT(text.size(), std::size_t{4} << 20);
  const auto path = fixture("rec.csv", text);
  const pipeline::Recording one = read_recording(path, {}, {}, 1);
  const pipeline::Recording two = read_recording(path, {}, {}, 2);
  EXPECT_TRUE(same_bits(one.time_s, two.time_s));
  ASSERT_EQ(one.channels.size(), 6u);
  ASSERT_EQ(two.channels.size(), 6u);
  for (std::size_t c = 0; c < 6; ++c)
    EXPECT_TRUE(same_bits(one.channels[c].values, two.channels[c].values));
  SeriesReadOptions options;
  options.column = "accel_z_m_per_s2";
  options.threads = 1;
  const Series s1 = read_series(path, options);
  options.threads = 3;
  const Series s3 = read_series(path, options);
  EXPECT_TRUE(same_bits(s1.values, s3.values));
  EXPECT_EQ(s1.values.size(), 40000u);
}

}  // namespace
}  // namespace imunoise::io
