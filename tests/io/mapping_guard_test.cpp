// io/mapping_guard: a read past the end of a file that shrank under its mapping reads zeros
// and is recorded inside a guarded range, and still takes its default course outside it.
#include "io/mapping_guard.h"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <filesystem>
#include <string>

#include "test_support.h"

namespace imunoise::io {
namespace {

/// A read-only private mapping of a file of PAGES pages of 'x', unmapped on destruction.
struct MappedFixture {
  std::filesystem::path path;
  std::size_t page = static_cast<std::size_t>(::sysconf(_SC_PAGESIZE));
  std::size_t size = 0;
  const volatile char* data = nullptr;

  MappedFixture(const std::string& name, std::size_t pages) {
    path = test::make_temp_dir("mapguard") / name;
    size = pages * page;
    test::write_text(path, std::string(size, 'x'));
    const int fd = ::open(path.c_str(), O_RDONLY);
    void* at = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE, fd, 0);
    ::close(fd);
    if (at != MAP_FAILED) data = static_cast<const volatile char*>(at);
  }
  ~MappedFixture() {
    if (data != nullptr) ::munmap(const_cast<char*>(data), size);
  }
  void shrink_to_pages(std::size_t pages) const {
    std::filesystem::resize_file(path, pages * page);
  }
};

TEST(MappingGuard, APagePastTheNewEndReadsZerosAndIsRecorded) {
  MappedFixture file("three_pages.bin", 3);
  ASSERT_NE(file.data, nullptr);
  MappingGuard guard(const_cast<const char*>(file.data), file.size);
  EXPECT_EQ(file.data[0], 'x');
  EXPECT_FALSE(guard.truncated());
  file.shrink_to_pages(1);
  EXPECT_EQ(file.data[0], 'x');  // still inside the file
  EXPECT_FALSE(guard.truncated());
  EXPECT_EQ(file.data[2 * file.page + 17], '\0');  // past the new end: faults, reads zero
  EXPECT_TRUE(guard.truncated());
  EXPECT_EQ(file.data[file.page], '\0');
}

TEST(MappingGuard, GuardsAreIndependent) {
  MappedFixture a("a.bin", 2);
  MappedFixture b("b.bin", 2);
  ASSERT_NE(a.data, nullptr);
  ASSERT_NE(b.data, nullptr);
  MappingGuard guard_a(const_cast<const char*>(a.data), a.size);
  MappingGuard guard_b(const_cast<const char*>(b.data), b.size);
  b.shrink_to_pages(1);
  EXPECT_EQ(b.data[b.page], '\0');
  EXPECT_FALSE(guard_a.truncated());
  EXPECT_TRUE(guard_b.truncated());
}

TEST(MappingGuardDeathTest, AFaultOutsideEveryGuardedRangeStillKillsTheProcess) {
  // The handler must not swallow faults it does not own: a shrunk mapping without a guard,
  // while another mapping is guarded, dies of its SIGBUS as it would without the handler.
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(
      {
        MappedFixture guarded("guarded.bin", 2);
        MappingGuard guard(const_cast<const char*>(guarded.data), guarded.size);
        MappedFixture bare("bare.bin", 2);
        bare.shrink_to_pages(1);
        volatile char c = bare.data[bare.page];
        (void)c;
      },
      "");
}

}  // namespace
}  // namespace imunoise::io
