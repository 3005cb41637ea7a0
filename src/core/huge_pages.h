// Transparent huge pages for large buffers.
//
// A large buffer first touched in 4 KB pages costs one minor fault per page; in a
// paravirtualised kernel those faults are a visible part of a big solve (docs/findings.md,
// "Page faults"). Where the kernel offers transparent huge pages on request
// (/sys/kernel/mm/transparent_hugepage/enabled = madvise), asking for them on a buffer before it
// is touched lets its 2 MB-aligned interior be backed by 2 MB pages. The advice changes no value
// and no layout: it is a hint the kernel may ignore.
#pragma once

#include <cstddef>
#include <vector>

namespace cb {

// Buffers from this size on are advised (smaller ones span at most one whole huge page).
constexpr std::size_t kHugePageAdviceBytes = std::size_t{4} << 20;

// Asks for huge pages on the 2 MB-aligned pages inside [data, data + bytes) when bytes is at
// least kHugePageAdviceBytes; does nothing elsewhere or where the system has no madvise.
// Returns whether the advice was given and accepted.
bool AdviseHugePages(void* data, std::size_t bytes);

// Gives *v room for n elements, advised before anything touches it (a vector that had the room
// already keeps its pages as they are).
template <class T>
void ReserveOnHugePages(std::vector<T>* v, std::size_t n) {
  if (v->capacity() >= n) return;
  v->reserve(n);
  AdviseHugePages(v->data(), n * sizeof(T));
}

// malloc, calloc and realloc that advise huge pages on what they return (free is the plain
// one: the blocks are ordinary malloc blocks). For allocator hooks such as SuiteSparse's.
void* HugePageMalloc(std::size_t bytes);
void* HugePageCalloc(std::size_t count, std::size_t size);
void* HugePageRealloc(void* data, std::size_t bytes);

}  // namespace cb
