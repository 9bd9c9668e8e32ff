// Counts every allocation of the program it is linked into (count_allocations.cpp
// replaces the global operator new): a test or benchmark reads the count before and
// after the code it watches. Link count_allocations.cpp into one program only once.
#pragma once

#include <cstdint>

namespace fts::test {

// Allocations through operator new since the program started.
std::uint64_t allocations_so_far();

}  // namespace fts::test
