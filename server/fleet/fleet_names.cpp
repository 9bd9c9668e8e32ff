#include "fleet/fleet_names.hpp"

#include <algorithm>

#include <nlohmann/json.hpp>

namespace fts::server {
namespace {

std::uint64_t seats_capacity(std::uint32_t max_rooms, std::uint32_t max_players) {
  return std::uint64_t{max_rooms} * max_players;
}
std::uint64_t rooms_capacity(std::uint32_t max_rooms, std::uint32_t) {
  return std::min<std::uint64_t>(max_rooms, kAgonesListMax);
}
std::uint64_t players_capacity(std::uint32_t max_rooms, std::uint32_t max_players) {
  return std::min<std::uint64_t>(seats_capacity(max_rooms, max_players), kAgonesListMax);
}

}  // namespace

// A GameServerAllocation selects by these: seats minAvailable (a free seat) for quick play,
// rooms minAvailable (a free room slot) and containsValue (join code X).
const std::array<FleetName, kFleetNameCount> kFleetNames = {{
    {FleetKind::counter, "seats", "seats_taken",
     "seats taken in all rooms (a player's, connected or away with the slot held; spectators take none), so "
     "capacity - count is the joins the server would take",
     "max_rooms x max_players", seats_capacity},
    {FleetKind::list, "rooms", "room_codes",
     "codes of the open rooms, private ones too, in room-id order (an older room keeps its place)",
     "min(max_rooms, 1000)", rooms_capacity},
    {FleetKind::list, "players", "player_names", "names of the connected players", "min(max_rooms x max_players, 1000)",
     players_capacity},
}};

const char* to_string(FleetKind kind) { return kind == FleetKind::counter ? "counter" : "list"; }

std::optional<std::size_t> fleet_row(FleetKind kind, std::string_view name) {
  for (std::size_t i = 0; i < kFleetNames.size(); ++i)
    if (kFleetNames[i].kind == kind && name == kFleetNames[i].name) return i;
  return std::nullopt;
}

std::string fleet_names_json_lines(std::uint32_t max_rooms, std::uint32_t max_players) {
  std::string out;
  for (const auto& row : kFleetNames)
    out += nlohmann::json{{"kind", to_string(row.kind)},
                          {"name", row.name},
                          {"holds", row.holds},
                          {"capacity", row.capacity(max_rooms, max_players)},
                          {"meaning", row.meaning},
                          {"capacity_rule", row.capacity_rule}}
               .dump() +
           "\n";
  return out;
}

}  // namespace fts::server
