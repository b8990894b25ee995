#include "io/mapping_guard.h"

#include <signal.h>
#include <sys/mman.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cstdint>
#include <mutex>
#include <stdexcept>

namespace imunoise::io {

namespace {

// The handler may run on any thread at any time, so everything it reads is a lock-free atomic
// in static storage, and it calls only mmap and sigaction (system calls).
struct Slot {
  std::atomic<std::uintptr_t> begin{0};  // 0: free
  std::atomic<std::uintptr_t> end{0};
  std::atomic<bool> hit{false};
};
constexpr std::size_t kSlots = 64;
std::array<Slot, kSlots> slots;
std::atomic<std::uintptr_t> page_size{0};
struct sigaction previous {};
std::mutex install_mutex;  // installs and slot claims; never taken by the handler
bool installed = false;

void on_sigbus(int signal, siginfo_t* info, void* context) {
  const auto address = reinterpret_cast<std::uintptr_t>(info->si_addr);
  const std::uintptr_t page = page_size.load(std::memory_order_relaxed);
  for (Slot& slot : slots) {
    const std::uintptr_t begin = slot.begin.load(std::memory_order_acquire);
    if (begin == 0 || address < begin || address >= slot.end.load(std::memory_order_acquire)) {
      continue;
    }
    void* at = reinterpret_cast<void*>(address / page * page);
    if (::mmap(at, page, PROT_READ, MAP_PRIVATE | MAP_ANONYMOUS | MAP_FIXED, -1, 0) != MAP_FAILED) {
      slot.hit.store(true, std::memory_order_release);
      return;  // the read is retried and sees zeros
    }
    break;
  }
  // Not ours (or the page could not be replaced): the previous disposition decides.
  if ((previous.sa_flags & SA_SIGINFO) != 0 && previous.sa_sigaction != nullptr) {
    previous.sa_sigaction(signal, info, context);
    return;
  }
  if (previous.sa_handler != SIG_DFL && previous.sa_handler != SIG_IGN &&
      previous.sa_handler != nullptr) {
    previous.sa_handler(signal);
    return;
  }
  ::sigaction(SIGBUS, &previous, nullptr);  // the fault repeats and takes its default course
}

}  // namespace

MappingGuard::MappingGuard(const void* begin, std::size_t size) {
  const std::lock_guard<std::mutex> lock(install_mutex);
  if (!installed) {
    page_size.store(static_cast<std::uintptr_t>(::sysconf(_SC_PAGESIZE)));
    struct sigaction action {};
    action.sa_sigaction = on_sigbus;
    action.sa_flags = SA_SIGINFO;
    sigemptyset(&action.sa_mask);
    if (::sigaction(SIGBUS, &action, &previous) != 0) {
      throw std::runtime_error("cannot install the SIGBUS handler for file mappings");
    }
    installed = true;
  }
  for (slot_ = 0; slot_ < kSlots; ++slot_) {
    if (slots[slot_].begin.load() == 0) break;
  }
  if (slot_ == kSlots) throw std::runtime_error("too many file mappings guarded at once");
  Slot& slot = slots[slot_];
  slot.hit.store(false);
  slot.end.store(reinterpret_cast<std::uintptr_t>(begin) + size);
  slot.begin.store(reinterpret_cast<std::uintptr_t>(begin), std::memory_order_release);
}

MappingGuard::~MappingGuard() {
  const std::lock_guard<std::mutex> lock(install_mutex);
  slots[slot_].begin.store(0, std::memory_order_release);
}

bool MappingGuard::truncated() const { return slots[slot_].hit.load(std::memory_order_acquire); }

}  // namespace imunoise::io
