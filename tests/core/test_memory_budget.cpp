// Limits from memory: estimates checked against the memory available, which
// DNURBS_MEMORY_LIMIT can lower.

#include "dnurbs/core/memory_budget.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "dnurbs/core/error.h"
#include "tests/common/error_message.h"

namespace dnurbs {
namespace {

using ::testing::HasSubstr;

// Sets DNURBS_MEMORY_LIMIT for one scope
class MemoryLimit {
 public:
  explicit MemoryLimit(const char* value) { ::setenv("DNURBS_MEMORY_LIMIT", value, 1); }
  MemoryLimit(const MemoryLimit&) = delete;
  MemoryLimit& operator=(const MemoryLimit&) = delete;
  ~MemoryLimit() { ::unsetenv("DNURBS_MEMORY_LIMIT"); }
};

TEST(MemoryBudget, TheLimitLowersWhatIsAvailableAndEstimatesAboveItAreRefused) {
  const std::uint64_t machine = available_memory_bytes();
  EXPECT_GT(machine, std::uint64_t{100} << 20);  // some memory is free
  {
    const MemoryLimit limit("1e9");
    EXPECT_EQ(available_memory_bytes(), std::min<std::uint64_t>(1000000000, machine));
    EXPECT_NO_THROW(check_memory_budget(0.9e9, "a mesh", "the resolution"));
    const auto refusal = [](double bytes, const char* what) {
      return testing::error_message([&] { check_memory_budget(bytes, what, "the resolution"); });
    };
    EXPECT_EQ(refusal(2.5e9, "a mesh of 10 x 10 cells"),
              "a mesh of 10 x 10 cells needs about 2500 MB, more than the 1000 MB of memory "
              "available; lower the resolution");
    EXPECT_EQ(refusal(3e30, "a mesh"),
              "a mesh needs about 3e+24 MB, more than the 1000 MB of memory available; lower "
              "the resolution");
    EXPECT_EQ(refusal(std::numeric_limits<double>::infinity(), "a mesh"),
              "a mesh needs about inf MB, more than the 1000 MB of memory available; lower "
              "the resolution");
    EXPECT_THROW(check_memory_budget(std::numeric_limits<double>::quiet_NaN(), "x", "y"), Error);
  }
  for (const char* ignored : {"abc", "-5", "0", "1e9x", ""}) {
    const MemoryLimit limit(ignored);
    EXPECT_GT(available_memory_bytes(), std::uint64_t{1} << 30) << ignored;
  }
}

TEST(MemoryBudget, MeshEstimateGrowsWithVerticesAndTriangles) {
  EXPECT_DOUBLE_EQ(triangle_mesh_bytes(0, 0), 0.0);
  EXPECT_DOUBLE_EQ(triangle_mesh_bytes(1000, 2000), 650.0 * 1000 + 320.0 * 2000);
}

}  // namespace
}  // namespace dnurbs
