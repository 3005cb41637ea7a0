#include "core/huge_pages.h"

#include <cstdint>
#include <cstdlib>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace cb {

bool AdviseHugePages(void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;
  if (data == nullptr || bytes < kHugePageAdviceBytes) return false;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHugePage - 1) & ~(kHugePage - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHugePage - 1);
  if (last <= first) return false;
  // NOLINTNEXTLINE(performance-no-int-to-ptr): madvise takes the page-aligned address
  return madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE) == 0;
#else
  (void)data;
  (void)bytes;
  return false;
#endif
}

// NOLINTBEGIN(cppcoreguidelines-no-malloc): the hooks replace malloc and must return its blocks
void* HugePageMalloc(std::size_t bytes) {
  void* data = std::malloc(bytes);
  AdviseHugePages(data, bytes);
  return data;
}

void* HugePageCalloc(std::size_t count, std::size_t size) {
  void* data = std::calloc(count, size);
  if (data != nullptr) AdviseHugePages(data, count * size);
  return data;
}

void* HugePageRealloc(void* data, std::size_t bytes) {
  void* moved = std::realloc(data, bytes);
  AdviseHugePages(moved, bytes);
  return moved;
}
// NOLINTEND(cppcoreguidelines-no-malloc)

}  // namespace cb
