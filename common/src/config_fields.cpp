#include "fts/sim/config_fields.hpp"

#include <cstddef>

namespace fts::sim {
namespace {

// The list names every member, in declaration order: laid out one after the other with
// their alignments, the listed members fill MatchConfig exactly. A member missing from
// the list (or listed out of order) leaves a hole this finds at compile time.
struct Slot {
  std::size_t offset, size, align;
};
#define FTS_SLOT(name, ...) Slot{offsetof(MatchConfig, name), sizeof(MatchConfig::name), alignof(decltype(MatchConfig::name))},
#define FTS_SLOT_HOST(name) FTS_SLOT(name)
constexpr Slot kSlots[] = {FTS_MATCH_CONFIG_FIELDS(FTS_SLOT, FTS_SLOT_HOST)};
#undef FTS_SLOT_HOST
#undef FTS_SLOT

constexpr bool listed_in_order() {
  std::size_t end = 0;
  for (const Slot& s : kSlots) {
    const std::size_t at = (end + s.align - 1) / s.align * s.align;
    if (s.offset != at) return false;
    end = at + s.size;
  }
  return (end + alignof(MatchConfig) - 1) / alignof(MatchConfig) * alignof(MatchConfig) == sizeof(MatchConfig);
}
static_assert(listed_in_order(), "FTS_MATCH_CONFIG_FIELDS must list every MatchConfig member, in declaration order");

}  // namespace

MatchConfig client_part(const MatchConfig& cfg) {
  MatchConfig out;
#define FTS_COPY(name, ...) out.name = cfg.name;
#define FTS_SKIP(name)
  FTS_MATCH_CONFIG_FIELDS(FTS_COPY, FTS_SKIP)
#undef FTS_SKIP
#undef FTS_COPY
  return out;
}

}  // namespace fts::sim
