// Typed ids, as Box2D's id structs: each kind of id is its own type, so a ball's id
// cannot stand for a player's, nor be added to, nor be read as a number by accident.
// An id is made from the number it is (a counter, the wire, a session slot, a test) and
// read back as .value. Zero is null. Ordered by value: containers iterate by id.
#pragma once

#include <compare>
#include <cstdint>

namespace fts::sim {

template <class Tag>
struct Id {
  std::uint32_t value = 0;

  constexpr Id() = default;
  constexpr Id(std::uint32_t v) : value(v) {}  // NOLINT(google-explicit-constructor): ids come from numbers
  constexpr explicit operator bool() const { return value != 0; }
  friend constexpr bool operator==(Id, Id) = default;
  friend constexpr auto operator<=>(Id, Id) = default;
};

// JSON (nlohmann finds this by ADL; common includes no JSON library): an id is its number.
template <class Json, class Tag>
void to_json(Json& j, const Id<Tag>& id) {
  j = id.value;
}

using BallId = Id<struct BallIdTag>;
using PlayerId = Id<struct PlayerIdTag>;  // chosen by the caller (the server's session slot)

}  // namespace fts::sim
