// End-to-end tests of `imunoise allan`: JSON shape and values against SP 1065, the human
// table, and the exit code and one-line message of every bad-input case.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace imunoise::test {
namespace {

using ::testing::HasSubstr;

std::filesystem::path nbs9_file(const std::filesystem::path& dir) {
  const auto path = dir / "nbs9.txt";
  write_text(path, "# NBS 9-point frequency set\n892\n809\n823\n798\n671\n644\n883\n903\n677\n");
  return path;
}

TEST(AllanCli, JsonIsOneObjectWithPublishedValues) {
  const auto dir = make_temp_dir("allan");
  const auto r = run_imunoise("allan '" + nbs9_file(dir).string() +
                              "' --type oadev --taus 1,2 --tau0 1 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);  // throws if stdout is not exactly one object
  EXPECT_EQ(j["type"], "oadev");
  EXPECT_EQ(j["data"], "rate");
  EXPECT_EQ(j["tau0_s"], 1.0);
  EXPECT_EQ(j["n_samples"], 9);
  EXPECT_DOUBLE_EQ(j["confidence"].get<double>(), 0.683);
  ASSERT_EQ(j["points"].size(), 2u);
  // SP 1065 9-point set: OADEV 91.22945 (m=1), 85.95287 (m=2).
  EXPECT_NEAR(j["points"][0]["value"].get<double>(), 91.22945, 91.22945 * 4e-7);
  EXPECT_NEAR(j["points"][1]["value"].get<double>(), 85.95287, 85.95287 * 4e-7);
  EXPECT_EQ(j["points"][0]["m"], 1);
  EXPECT_EQ(j["points"][0]["n_terms"], 8);
  for (const auto& p : j["points"]) {
    EXPECT_LT(p["ci_low"].get<double>(), p["value"].get<double>());
    EXPECT_GT(p["ci_high"].get<double>(), p["value"].get<double>());
    EXPECT_GT(p["edf"].get<double>(), 0.0);
  }
}

TEST(AllanCli, PhaseDataFromNistFileMatchesPublishedOadev) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto r =
      run_imunoise("allan '" + (data / "nist-sp1065-nbs" / "nbs14_1000_phase.csv").string() +
                   "' --column x --data phase --type oadev --taus 1,10,100 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["n_samples"], 1001);
  const double published[] = {2.922319e-01, 9.159953e-02, 3.241343e-02};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(j["points"][i]["value"].get<double>() / published[i], 1.0, 5e-7);
  }
}

TEST(AllanCli, HumanTableListsEveryTau) {
  const auto dir = make_temp_dir("allan");
  const auto r = run_imunoise("allan '" + nbs9_file(dir).string() + "' --type adev --taus octave");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("adev"));
  EXPECT_THAT(r.out, HasSubstr("ci_low"));
  EXPECT_THAT(r.out, HasSubstr("9.122945e+01"));
}

TEST(AllanCli, TooFewSamplesForRequestedTauIsAnErrorNamingTheFile) {
  const auto dir = make_temp_dir("allan");
  const auto file = nbs9_file(dir);
  const auto r = run_imunoise("allan '" + file.string() + "' --taus 1,5");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.err, HasSubstr(file.string()));
  EXPECT_THAT(r.err, HasSubstr("too few samples for the requested tau"));
  EXPECT_TRUE(r.out.empty());
}

TEST(AllanCli, MalformedNumberNamesFileLineAndColumn) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "bad.txt";
  write_text(file, "1.0\n2.0\n3.0x\n4.0\n");
  const auto r = run_imunoise("allan '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr(file.string() + ":3:1"));
  EXPECT_THAT(r.err, HasSubstr("3.0x"));
}

TEST(AllanCli, UnknownColumnListsAvailableOnes) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "two.csv";
  write_text(file, "a,b\n1,2\n3,4\n5,6\n7,8\n9,10\n");
  const auto r = run_imunoise("allan '" + file.string() + "' --column c");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("'c'"));
  EXPECT_THAT(r.err, HasSubstr("a"));
  EXPECT_THAT(r.err, HasSubstr("b"));
}

TEST(AllanCli, NonFiniteValuesFailUnlessDropped) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "nan.txt";
  write_text(file, "1\n2\nnan\n4\n5\n6\n7\n8\n9\n10\n");
  const auto fail = run_imunoise("allan '" + file.string() + "'");
  EXPECT_EQ(fail.exit_code, 2);
  EXPECT_THAT(fail.err, HasSubstr(":3"));
  const auto ok = run_imunoise("allan '" + file.string() + "' --drop-non-finite --json");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const auto j = nlohmann::json::parse(ok.out);
  EXPECT_EQ(j["non_finite_dropped"], 1);
  EXPECT_EQ(j["n_samples"], 9);
}

TEST(AllanCli, BadFlagsAreRejected) {
  const auto dir = make_temp_dir("allan");
  const auto file = nbs9_file(dir).string();
  EXPECT_NE(run_imunoise("allan '" + file + "' --type foo").exit_code, 0);
  EXPECT_NE(run_imunoise("allan '" + file + "' --taus log:x").exit_code, 0);
  EXPECT_NE(run_imunoise("allan '" + file + "' --tau0 -1").exit_code, 0);
  EXPECT_NE(run_imunoise("allan '" + file + "' --confidence 1.5").exit_code, 0);
  const auto missing = run_imunoise("allan /nonexistent/file.txt");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(missing.err, HasSubstr("/nonexistent/file.txt"));
}

TEST(AllanCli, EmptyFileIsAClearError) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "empty.txt";
  write_text(file, "# only a comment\n");
  const auto r = run_imunoise("allan '" + file.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr(file.string()));
}

}  // namespace
}  // namespace imunoise::test

namespace imunoise::test {
namespace {

TEST(AllanCli, Tau0ComesFromTheTimeColumnWhenNotGiven) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "rec.csv";
  std::string text = "time_ms,gyro_x_rad_per_s\n";
  for (int i = 0; i < 200; ++i) {
    text += std::to_string(1000 + 10 * i) + "," + std::to_string((i * 7919) % 13 - 6) + "\n";
  }
  write_text(file, text);
  const auto r = run_imunoise("allan '" + file.string() + "' --column gyro_x_rad_per_s --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["tau0_s"].get<double>(), 0.01, 1e-15);  // 10 ms stamps, scaled to s
  EXPECT_THAT(j["tau0_source"].get<std::string>(), HasSubstr("time_ms"));
  EXPECT_NEAR(j["points"][1]["tau_s"].get<double>(), 0.02, 1e-15);
  EXPECT_TRUE(r.err.empty()) << r.err;
  // An explicit --tau0 wins over the time column.
  const auto given =
      run_imunoise("allan '" + file.string() + "' --column gyro_x_rad_per_s --tau0 2 --json");
  ASSERT_EQ(given.exit_code, 0) << given.err;
  EXPECT_EQ(nlohmann::json::parse(given.out)["tau0_s"], 2.0);
}

TEST(AllanCli, GapsInTheTimeColumnAreWarnedAbout) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "gappy.csv";
  std::string text = "time_s,y\n";
  for (int i = 0; i < 100; ++i) {
    const double t = i < 50 ? i * 0.5 : i * 0.5 + 10.0;  // one 10.5 s interval
    text += std::to_string(t) + "," + std::to_string(i % 7) + "\n";
  }
  write_text(file, text);
  const auto r = run_imunoise("allan '" + file.string() + "' --column y --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_DOUBLE_EQ(nlohmann::json::parse(r.out)["tau0_s"].get<double>(), 0.5);
  EXPECT_THAT(r.err, HasSubstr("1 gap(s)"));
  EXPECT_THAT(r.err, HasSubstr("uniform sampling"));
}

}  // namespace
}  // namespace imunoise::test

namespace imunoise::test {
namespace {

// SP 1065 published MTOTDEV with bias correction for the NBS14 set: 2.418528e-01 (m=1),
// 6.499161e-02 (m=10), 2.287774e-02 (m=100); the CLI path with --bias-correction and the
// white-FM alpha reproduces them.
TEST(AllanCli, BiasCorrectedMtotdevMatchesSp1065) {
  IMUNOISE_REQUIRE_REFERENCE_DATA(data);
  const auto r =
      run_imunoise("allan '" + (data / "nist-sp1065-nbs" / "nbs14_1000_phase.csv").string() +
                   "' --column x --data phase --type mtotdev --taus 1,10,100 --bias-correction "
                   "--alpha 0 --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["bias_corrected"], true);
  const double published[] = {2.418528e-01, 6.499161e-02, 2.287774e-02};
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(j["points"][i]["value"].get<double>() / published[i], 1.0, 5e-7);
  }
}

TEST(AllanCli, Theo1UsesEvenFactorsAndThreeQuarterTau) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "y.txt";
  std::string text;
  for (int i = 0; i < 400; ++i) text += std::to_string((i * 7919) % 101) + "\n";
  write_text(file, text);
  const auto r = run_imunoise("allan '" + file.string() + "' --type theo1 --taus decade --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const auto& p : j["points"]) {
    EXPECT_EQ(p["m"].get<int>() % 2, 0);
    EXPECT_DOUBLE_EQ(p["tau_s"].get<double>(), 0.75 * p["m"].get<double>());
  }
  const auto odd = run_imunoise("allan '" + file.string() + "' --type theo1 --taus 3");
  EXPECT_EQ(odd.exit_code, 3);
  EXPECT_THAT(odd.err, HasSubstr("even"));
}

TEST(AllanCli, QuadraticCostStatisticsRefuseHugeGridsInsteadOfHanging) {
  const auto dir = make_temp_dir("allan");
  const auto file = dir / "long.txt";
  std::string text;
  for (int i = 0; i < 300000; ++i) text += std::to_string(i % 13) + "\n";
  write_text(file, text);
  const auto r = run_imunoise("allan '" + file.string() + "' --type mtotdev --taus log:10");
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_THAT(r.err, HasSubstr("O(M·m)"));
}

}  // namespace
}  // namespace imunoise::test
