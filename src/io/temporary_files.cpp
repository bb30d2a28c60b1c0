#include "io/temporary_files.hpp"

#include <unistd.h>

#include <atomic>
#include <cstring>

namespace periadapt {

namespace {

constexpr int kSlots = 8;
constexpr std::size_t kPathMax = 4096;

// 0 free, 1 being filled, 2 holds a path the signal handler may unlink.
std::atomic<int> g_state[kSlots];
char g_path[kSlots][kPathMax];

static_assert(std::atomic<int>::is_always_lock_free, "read from a signal handler");

}  // namespace

TemporaryFileGuard::TemporaryFileGuard(const std::string& path) {
  if (path.size() + 1 > kPathMax) return;
  for (int k = 0; k < kSlots; ++k) {
    int expected = 0;
    if (!g_state[k].compare_exchange_strong(expected, 1)) continue;
    std::memcpy(g_path[k], path.c_str(), path.size() + 1);
    g_state[k].store(2);
    slot_ = k;
    return;
  }
}

TemporaryFileGuard::~TemporaryFileGuard() {
  if (slot_ >= 0) g_state[slot_].store(0);
}

void remove_temporary_files_now() noexcept {
  for (int k = 0; k < kSlots; ++k)
    if (g_state[k].load() == 2) ::unlink(g_path[k]);
}

}  // namespace periadapt
