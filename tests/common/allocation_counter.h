#pragma once
// Counts calls of the global operator new while `count_allocations` is set. The replacement
// operator new and the counters are defined once, in allocation_counter.cpp.

#include <atomic>

namespace dnurbs::testing {
extern std::atomic<bool> count_allocations;
extern std::atomic<long> allocations;
}  // namespace dnurbs::testing
