// Zero-allocation proof: every core entry point on the decode path runs here while every heap
// allocation of the process is counted. Each subject is a TEST in this folder.
#include <gtest/gtest.h>

#include "alloc_counter.h"

// The harness itself must see an allocation, or every other test here proves nothing.
TEST(ZeroAllocationHarness, SeesOperatorNew) {
  int* volatile p = nullptr;
  const std::size_t n = hesai_test::allocations_during([&] { p = new int(7); });
  delete p;
  EXPECT_GE(n, 1u);
}

TEST(ZeroAllocationHarness, SeesMalloc) {
  if (!hesai_test::counts_malloc()) GTEST_SKIP() << "malloc belongs to the sanitizer here";
  void* volatile p = nullptr;
  const std::size_t n = hesai_test::allocations_during([&] { p = std::malloc(64); });
  std::free(p);
  EXPECT_GE(n, 1u);
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
