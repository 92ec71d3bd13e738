#pragma once
// The memory of CHOLMOD's factors. A remesh frees the old factor and allocates a new one of about
// the same size; the C library hands such large blocks back to the system when they are freed
// and takes fresh pages for the next one, which the kernel then faults in and zeroes one page at
// a time, a visible part of a remesh (docs/flow.md, "Measurements behind the code"). Here the
// large blocks SuiteSparse frees are kept, while a pressure solver exists, for its next factor.
#include <cstddef>

namespace talus::flow::pore
{
/// SuiteSparse's allocator (SuiteSparse_config: CHOLMOD's factors and workspaces), installed
/// when the library is loaded, before any CHOLMOD call (a block must go back to the allocator
/// that gave it). Blocks of kLargeBlock bytes and more are kept when freed while some User
/// exists, and given again to a request of at least half their size; the others go to malloc.
/// When the last User goes, the kept blocks are returned to the system.
class FactorMemory
{
public:
  /// Blocks from this size on are kept: a factor's values, indices and supernode maps. Smaller
  /// ones are malloc's, which keeps them in its heap anyway.
  static constexpr std::size_t kLargeBlock = std::size_t{4} << 20;

  /// Held by each pressure solver for its lifetime: while one exists, freed large blocks are kept.
  class User
  {
  public:
    User();
    ~User();
    User(const User&);
    User(User&&) noexcept;
    User& operator=(const User&) = default;
    User& operator=(User&&) noexcept = default;
  };

  /// Bytes of the blocks kept now (freed, waiting for the next factor).
  [[nodiscard]] static std::size_t keptBytes();
};
} // namespace talus::flow::pore
