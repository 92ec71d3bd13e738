#include "flow/pore/solver/FactorMemory.h"

#include <SuiteSparse_config.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <mutex>

namespace talus::flow::pore
{
namespace
{
/// At most this many blocks are kept (a factor has a few large arrays; more would be blocks of
/// older factors that no longer fit).
constexpr std::size_t kKeptBlocks = 16;

/// Each block starts with its capacity; the header keeps malloc's alignment for what follows.
struct alignas(alignof(std::max_align_t)) Header
{
  std::size_t capacity;
};

struct Kept
{
  std::mutex mutex;
  std::deque<Header*> blocks; ///< oldest first
  std::size_t bytes = 0;
  long users = 0;

  /// Returns the kept blocks to the system (the caller holds the mutex).
  void drop()
  {
    for (Header* h : blocks)
      std::free(h);
    blocks.clear();
    bytes = 0;
  }
};

/// Never destroyed: CHOLMOD may free a block while the process exits.
Kept& kept()
{
  static Kept* const k = new Kept;
  return *k;
}

void* allocate(std::size_t size)
{
  if (size >= FactorMemory::kLargeBlock)
  {
    Kept& k = kept();
    const std::lock_guard lock(k.mutex);
    auto best = k.blocks.end();
    for (auto it = k.blocks.begin(); it != k.blocks.end(); ++it)
      if ((*it)->capacity >= size && (*it)->capacity / 2 <= size &&
          (best == k.blocks.end() || (*it)->capacity < (*best)->capacity))
        best = it;
    if (best != k.blocks.end())
    {
      Header* h = *best;
      k.blocks.erase(best);
      k.bytes -= h->capacity;
      return h + 1;
    }
  }
  // a large block gets an eighth more than asked, so that the next factor, a little larger,
  // still fits (pages never touched cost no memory)
  const std::size_t capacity = size >= FactorMemory::kLargeBlock ? size + size / 8 : size;
  auto* h = static_cast<Header*>(std::malloc(sizeof(Header) + capacity));
  if (!h)
    return nullptr;
  h->capacity = capacity;
  return h + 1;
}

void release(void* p)
{
  if (!p)
    return;
  Header* h = static_cast<Header*>(p) - 1;
  if (h->capacity >= FactorMemory::kLargeBlock)
  {
    Kept& k = kept();
    const std::lock_guard lock(k.mutex);
    if (k.users > 0)
    {
      k.blocks.push_back(h);
      k.bytes += h->capacity;
      if (k.blocks.size() > kKeptBlocks)
      {
        k.bytes -= k.blocks.front()->capacity;
        std::free(k.blocks.front());
        k.blocks.pop_front();
      }
      return;
    }
  }
  std::free(h);
}

void* allocateZeroed(std::size_t count, std::size_t size)
{
  if (size != 0 && count > SIZE_MAX / size)
    return nullptr;
  void* p = allocate(count * size);
  if (p)
    std::memset(p, 0, count * size);
  return p;
}

void* reallocate(void* p, std::size_t size)
{
  if (!p)
    return allocate(size);
  Header* h = static_cast<Header*>(p) - 1;
  if (size <= h->capacity)
    return p;
  void* q = allocate(size);
  if (!q)
    return nullptr; // p stays valid, as realloc leaves it
  std::memcpy(q, p, h->capacity);
  release(p);
  return q;
}

const bool kInstalled = [] {
  SuiteSparse_config.malloc_func = allocate;
  SuiteSparse_config.calloc_func = allocateZeroed;
  SuiteSparse_config.realloc_func = reallocate;
  SuiteSparse_config.free_func = release;
  return true;
}();
} // namespace

FactorMemory::User::User()
{
  Kept& k = kept();
  const std::lock_guard lock(k.mutex);
  ++k.users;
}

FactorMemory::User::User(const User& /*other*/) : User() {}

FactorMemory::User::User(User&& /*other*/) noexcept : User() {}

FactorMemory::User::~User()
{
  Kept& k = kept();
  const std::lock_guard lock(k.mutex);
  if (--k.users == 0)
    k.drop();
}

std::size_t FactorMemory::keptBytes()
{
  Kept& k = kept();
  const std::lock_guard lock(k.mutex);
  return k.bytes;
}
} // namespace talus::flow::pore
