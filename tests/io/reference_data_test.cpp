// Reading the real reference files under ../shared/data (NIST SP 1065 CSVs, Stable32 data
// files from allantools): counts and first values as printed in the files themselves.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "common/errors.h"
#include "io/csv_reader.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

using ::testing::HasSubstr;

Series read(const std::filesystem::path& path, const std::string& column = "") {
  SeriesReadOptions options;
  options.column = column;
  return read_series(path.string(), options);
}

TEST(ReferenceData, Stable32PhaseDat) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
  // CRLF, two '#' comment lines, one value per line.
  const Series s = read(dir / "allantools-stable32/phasedat/PHASE.DAT");
  ASSERT_EQ(s.values.size(), 1001u);
  EXPECT_EQ(s.values[0], 0.0);
  EXPECT_EQ(s.values[1], 8.511601033439709e-02);
  EXPECT_EQ(s.values[2], -2.204754825860608e-01);
  EXPECT_EQ(s.values[1000], 9.908740494779522e-14);
  EXPECT_EQ(s.first_data_line, 3);
}

TEST(ReferenceData, NistNbs14PhaseColumnX) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
  const auto path = dir / "nist-sp1065-nbs/nbs14_1000_phase.csv";
  const Series s = read(path, "x");
  ASSERT_EQ(s.values.size(), 1001u);
  EXPECT_EQ(s.column_name, "x");
  EXPECT_EQ(s.values[0], 0.0);
  EXPECT_EQ(s.values[1], 0.085116010334396697);
  EXPECT_EQ(s.values[3], -0.14707417985148463);
  EXPECT_EQ(s.first_data_line, 2);
  // Same series by position.
  EXPECT_EQ(read(path, "2").values, s.values);
  // PHASE.DAT is the same data set, integrated separately: equal to ~1e-13 (rounding).
  const Series stable32 = read(dir / "allantools-stable32/phasedat/PHASE.DAT");
  for (std::size_t i = 0; i < s.values.size(); ++i) {
    ASSERT_NEAR(stable32.values[i], s.values[i], 1e-12) << "sample " << i;
  }
}

TEST(ReferenceData, NistCsvWithoutColumnListsColumns) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
  try {
    read(dir / "nist-sp1065-nbs/nbs14_1000_freq.csv");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_THAT(e.what(), HasSubstr("nbs14_1000_freq.csv:1: the file has 3 columns"));
    EXPECT_THAT(e.what(), HasSubstr("available columns: index, lcg_integer, y"));
  }
}

TEST(ReferenceData, NistNbs9Frequency) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
  const Series s = read(dir / "nist-sp1065-nbs/nbs9_freq.csv", "y");
  ASSERT_EQ(s.values.size(), 9u);
  EXPECT_EQ(s.values[0], 892.0);
  EXPECT_EQ(s.values[8], 677.0);
}

TEST(ReferenceData, OtherStable32DataFiles) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
  const Series pink = read(dir / "allantools-stable32/pink_frequency/pink_frequency.txt");
  ASSERT_EQ(pink.values.size(), 10000u);
  EXPECT_EQ(pink.values[0], 1.62551e-07);
  const Series ocxo = read(dir / "allantools-stable32/ocxo/ocxo_frequency.txt");
  ASSERT_EQ(ocxo.values.size(), 19982u);
  EXPECT_EQ(ocxo.values[0], 10000000.126856699585915);
  const Series tic = read(dir / "allantools-stable32/Keysight53230A_ti_noise_floor/tic_phase.txt");
  EXPECT_EQ(tic.values.size(), 55688u);
  EXPECT_EQ(tic.values[0], 1.0104e-08);
}

TEST(ReferenceData, Stable32ResultTableIsWhitespaceSeparated) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(dir);
  // `AF Tau # Alpha MinSigma Sigma MaxSigma` rows after '#' comments, no header row.
  const auto path = dir / "allantools-stable32/phasedat/phase_dat_adev_octave.txt";
  TableReader reader(path.string());
  EXPECT_EQ(reader.layout().delimiter, Delimiter::kWhitespace);
  EXPECT_FALSE(reader.layout().has_header());
  const Series sigma = read(path, "6");
  EXPECT_FALSE(sigma.values.empty());
}

}  // namespace
}  // namespace imunoise::io
