#pragma once

#include <cstddef>
#include <cstdlib>
#include <new>

#ifdef __linux__
#include <sys/mman.h>
#endif

namespace talus::dem
{
/// Allocator for the large arrays a step rebuilds (the contact list and its spare): blocks of
/// 2 MiB or more are aligned on 2 MiB and advised for transparent huge pages, so the kernel
/// fills them with 2 MiB pages where it allows (Linux's THP mode "madvise" or "always"),
/// smaller ones come from operator new.
///
/// Why: a re-detection that lengthens the contact list moves it to fresh memory, and every
/// first touch of a 4 KiB page is a page fault, dear in a virtual machine; a 2 MiB page takes
/// one fault for 512 small ones (docs/dem.md, "Measurements behind the code"). Where the kernel
/// refuses (THP "never", other systems) the advice is ignored and nothing changes but the
/// alignment.
template <class T>
struct HugePageAllocator
{
  using value_type = T;
  static constexpr std::size_t hugePage = std::size_t{2} << 20;

  /// Stateless: every instance can free what any other allocated.
  HugePageAllocator() = default;
  /// The rebinding constructor the standard containers need (no state to copy).
  template <class U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept // NOLINT(google-explicit-constructor): rebinding
  {
  }

  /// @param n the number of T
  /// @return storage for n T, 2 MiB-aligned and advised as huge pages from 2 MiB on (the size
  ///         rounded up to whole huge pages), plain aligned new below
  /// @throws std::bad_alloc when the memory cannot be had
  T* allocate(std::size_t n)
  {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < hugePage)
      return static_cast<T*>(::operator new(bytes, std::align_val_t(alignof(T))));
    const std::size_t rounded = (bytes + hugePage - 1) / hugePage * hugePage;
    void* block = std::aligned_alloc(hugePage, rounded);
    if (!block)
      throw std::bad_alloc();
#ifdef MADV_HUGEPAGE
    madvise(block, rounded, MADV_HUGEPAGE); // advice only: a refusal leaves 4 KiB pages
#endif
    return static_cast<T*>(block);
  }

  /// @param block what allocate(n) returned
  /// @param n the same count as given to allocate (it chooses how the block was obtained)
  void deallocate(T* block, std::size_t n) noexcept
  {
    if (n * sizeof(T) < hugePage)
      ::operator delete(block, std::align_val_t(alignof(T)));
    else
      std::free(block);
  }

  /// Always equal (stateless), so containers may swap and move their storage.
  template <class U>
  bool operator==(const HugePageAllocator<U>&) const noexcept
  {
    return true;
  }
  /// Never unequal (stateless).
  template <class U>
  bool operator!=(const HugePageAllocator<U>&) const noexcept
  {
    return false;
  }
};
} // namespace talus::dem
