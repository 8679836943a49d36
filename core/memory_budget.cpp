#include "dnurbs/core/memory_budget.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include "dnurbs/core/error.h"

namespace dnurbs {

namespace {

// MemAvailable of /proc/meminfo, else the physical memory
std::uint64_t machine_available_bytes() {
  std::ifstream meminfo("/proc/meminfo");
  std::string line;
  while (std::getline(meminfo, line)) {
    if (line.rfind("MemAvailable:", 0) == 0) {
      std::istringstream fields(line.substr(13));
      std::uint64_t kilobytes = 0;
      if (fields >> kilobytes) {
        return kilobytes * 1024;
      }
    }
  }
  const long pages = ::sysconf(_SC_PHYS_PAGES);
  const long page = ::sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0
             ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page)
             : UINT64_MAX;
}

}  // namespace

std::uint64_t available_memory_bytes() {
  std::uint64_t limit = UINT64_MAX;
  if (const char* text = std::getenv("DNURBS_MEMORY_LIMIT"); text != nullptr) {
    char* end = nullptr;
    const double value = std::strtod(text, &end);
    if (end != text && *end == '\0' && value > 0.0 && value < 1.8e19) {
      limit = static_cast<std::uint64_t>(value);
    }
  }
  return std::min(limit, machine_available_bytes());
}

void check_memory_budget(double bytes, const std::string& what, const std::string& lower) {
  const double available = static_cast<double>(available_memory_bytes());
  if (!(bytes <= available)) {
    // Whole MB; in exponent form past 1e12 MB (an absurd request, e.g. a resolution_scale of
    // 1e300, whose estimate may even be infinite)
    const auto megabytes = [](double b) {
      char text[32];
      std::snprintf(text, sizeof(text), b / 1e6 < 1e12 ? "%.0f" : "%.3g", b / 1e6);
      return std::string(text);
    };
    throw make_error(what, " needs about ", megabytes(bytes), " MB, more than the ",
                     megabytes(available), " MB of memory available; lower ", lower);
  }
}

}  // namespace dnurbs
