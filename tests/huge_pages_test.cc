// Huge-page advice: only for large buffers, and the hooks behave as malloc, calloc, realloc.
#include "core/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <vector>

namespace cb {
namespace {

TEST(HugePagesTest, SmallOrMissingBuffersAreNotAdvised) {
  std::vector<char> small(kHugePageAdviceBytes - 1);
  EXPECT_FALSE(AdviseHugePages(small.data(), small.size()));
  EXPECT_FALSE(AdviseHugePages(nullptr, 2 * kHugePageAdviceBytes));
}

// NOLINTBEGIN(cppcoreguidelines-no-malloc): the hooks' blocks are malloc blocks
TEST(HugePagesTest, HooksKeepMallocSemantics) {
  const std::size_t n = kHugePageAdviceBytes / sizeof(double) + 1000;  // advised where possible
  auto* zeros = static_cast<double*>(HugePageCalloc(n, sizeof(double)));
  ASSERT_NE(zeros, nullptr);
  for (std::size_t i = 0; i < n; i += 4097) EXPECT_EQ(zeros[i], 0.0);
  zeros[n - 1] = 0.0;
  std::free(zeros);
  auto* a = static_cast<double*>(HugePageMalloc(sizeof(double) * 100));
  ASSERT_NE(a, nullptr);
  for (int i = 0; i < 100; ++i) a[i] = i;
  auto* b = static_cast<double*>(HugePageRealloc(a, sizeof(double) * n));  // grows past advice
  ASSERT_NE(b, nullptr);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(b[i], i);
  b[n - 1] = 1.0;
  std::free(b);
}
// NOLINTEND(cppcoreguidelines-no-malloc)

}  // namespace
}  // namespace cb
