// The replacement global operator new behind tests/common/allocation_counter.h. In a file of its
// own so that no caller inlines it (g++ 12 then warns about malloc/free pairs it cannot match).
#include "tests/common/allocation_counter.h"

#include <cstdlib>
#include <new>

std::atomic<bool> dnurbs::testing::count_allocations{false};
std::atomic<long> dnurbs::testing::allocations{0};

void* operator new(std::size_t size) {
  if (dnurbs::testing::count_allocations.load()) {
    ++dnurbs::testing::allocations;
  }
  if (void* p = std::malloc(size == 0 ? 1 : size)) {
    return p;
  }
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t /*size*/) noexcept {
  std::free(p);
}
