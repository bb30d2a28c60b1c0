#include "core/process_memory.hpp"

#include <sys/resource.h>
#include <unistd.h>

#include <fstream>

namespace periadapt {

std::size_t peak_rss_bytes() {
  rusage ru{};
  if (getrusage(RUSAGE_SELF, &ru) != 0) return 0;
  return static_cast<std::size_t>(ru.ru_maxrss) * 1024;  // Linux reports kilobytes
}

std::size_t current_rss_bytes() {
  // /proc/self/statm: total and resident pages.
  std::ifstream in("/proc/self/statm");
  std::size_t total = 0, resident = 0;
  if (!(in >> total >> resident)) return 0;
  const long page = sysconf(_SC_PAGESIZE);
  return page > 0 ? resident * static_cast<std::size_t>(page) : 0;
}

}  // namespace periadapt
