/// @file
/// @brief reserve_huge_pages: room for a large array, backed by transparent huge pages where
/// the kernel allows them. A 24 h record at 1 kHz has 0.7 GB per channel; in 4 KiB pages that
/// is 170 000 page faults per array, each zeroing one page, and the recording, the phase
/// records and the PSD touch about 18 such arrays. With 2 MiB pages the faults drop 512-fold:
/// filling a fresh 0.7 GB vector took 0.37–0.48 s with the hint and 0.67–0.84 s without on the
/// bench machine (bench/RESULTS.md). The hint changes no value; where the kernel refuses it
/// (THP "never", other systems) nothing changes at all.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace imunoise {

/// Asks for transparent huge pages on the whole 2 MiB pages inside [data, data + bytes).
/// Only pages not yet touched are affected, so call it before the first write.
inline void advise_huge_pages(void* data, std::size_t bytes) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t{1} << 21;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHuge - 1);
  if (last > first) {
    // Advice only: a refusal (EINVAL where THP is compiled out) leaves ordinary pages.
    static_cast<void>(::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE));
  }
#else
  static_cast<void>(data);
  static_cast<void>(bytes);
#endif
}

/// Empties V and reserves room for N elements, with the huge-page advice on that room (below
/// 4 MiB it is not worth a system call). Fill V afterwards (push_back, insert, resize).
template <typename T>
void reserve_huge_pages(std::vector<T>& v, std::size_t n) {
  std::vector<T>().swap(v);
  v.reserve(n);
  if (n * sizeof(T) >= (std::size_t{4} << 20)) advise_huge_pages(v.data(), n * sizeof(T));
}

}  // namespace imunoise
