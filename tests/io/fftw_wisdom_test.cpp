// FFTW wisdom files (io/fftw_wisdom): distinct errors for a file that cannot be opened and one
// that is not wisdom, an export that imports back, and an export that fails leaving no file.
// FFTW wisdom is process-global: each test starts and ends with none, so the order does not
// matter.
#include "io/fftw_wisdom.h"

#include <fftw3.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <mutex>
#include <string>

#include "common/errors.h"
#include "common/fftw_planner_lock.h"
#include "test_support.h"

namespace imunoise::io {
namespace {

constexpr int kLength = 256;

/// Plans an r2c transform of kLength with FLAGS; true when FFTW gave a plan (destroyed here).
bool can_plan(unsigned flags) {
  const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
  double* in = fftw_alloc_real(kLength);
  fftw_complex* out = fftw_alloc_complex(kLength / 2 + 1);
  fftw_plan plan = fftw_plan_dft_r2c_1d(kLength, in, out, flags);
  const bool planned = plan != nullptr;
  if (plan != nullptr) fftw_destroy_plan(plan);
  fftw_free(in);
  fftw_free(out);
  return planned;
}

class FftwWisdom : public ::testing::Test {
 protected:
  static void forget() {
    const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
    fftw_forget_wisdom();
  }
  void SetUp() override { forget(); }
  void TearDown() override { forget(); }
};

TEST_F(FftwWisdom, MissingFileIsAnInputErrorNamingItThatSaysCannotOpen) {
  const auto path = test::make_temp_dir("wisdom_missing") / "none.wisdom";
  const std::string message = test::error_of([&] { import_fftw_wisdom(path.string()); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_NE(message.find("cannot open the FFTW wisdom file"), std::string::npos) << message;
  EXPECT_NE(message.find("No such file"), std::string::npos) << message;
}

TEST_F(FftwWisdom, GarbageAndEmptyFilesAreNotWisdom) {
  const auto dir = test::make_temp_dir("wisdom_garbage");
  for (const std::string& content : {std::string("this is not wisdom\n"), std::string()}) {
    const auto path = dir / "bad.wisdom";
    test::write_text(path, content);
    const std::string message = test::error_of([&] { import_fftw_wisdom(path.string()); });
    EXPECT_NE(message.find(path.string()), std::string::npos) << message;
    EXPECT_NE(message.find("not an FFTW wisdom file"), std::string::npos) << message;
    EXPECT_EQ(message.find("cannot open"), std::string::npos) << message;
  }
  // A directory opens but cannot be read: a third, distinct message.
  const std::string message = test::error_of([&] { import_fftw_wisdom(dir.string()); });
  EXPECT_NE(message.find("cannot read the FFTW wisdom file"), std::string::npos) << message;
}

TEST_F(FftwWisdom, ExportWritesAFileThatImportsBack) {
  const auto path = test::make_temp_dir("wisdom_export") / "plans.wisdom";
  ASSERT_TRUE(can_plan(FFTW_MEASURE));  // measures: the process now has the wisdom
  export_fftw_wisdom(path.string());
  ASSERT_TRUE(std::filesystem::exists(path));
  EXPECT_EQ(test::read_file_bytes(path).rfind("(fftw-", 0), 0u);
  forget();
  EXPECT_FALSE(can_plan(FFTW_MEASURE | FFTW_WISDOM_ONLY));
  import_fftw_wisdom(path.string());
  EXPECT_TRUE(can_plan(FFTW_MEASURE | FFTW_WISDOM_ONLY));
}

TEST_F(FftwWisdom, ExportIntoAMissingDirectoryFailsAndLeavesNoFile) {
  const auto dir = test::make_temp_dir("wisdom_nodir");
  const auto path = dir / "missing" / "plans.wisdom";
  const std::string message = test::error_of([&] { export_fftw_wisdom(path.string()); });
  EXPECT_NE(message.find(path.string()), std::string::npos) << message;
  EXPECT_FALSE(std::filesystem::exists(dir / "missing"));
  EXPECT_TRUE(std::filesystem::is_empty(dir));  // no temporary file either
}

}  // namespace
}  // namespace imunoise::io
