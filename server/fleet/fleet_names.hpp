// The Counters and Lists fts-server keeps in its Agones GameServer: the one definition of
// their names, what each holds and how its capacity follows from the server's limits. The
// SDK client (agones_sync) and the metrics take the names from here; the manifests in
// docker/agones/ are checked against it by hosting_agones_manifests, which asks the built
// server (`fts-server --print-fleet-names`, a hidden flag) rather than reading this file.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace fts::server {

enum class FleetKind { counter, list };

struct FleetName {
  FleetKind kind;
  const char* name;           // the key under the GameServer's spec.counters or spec.lists
  const char* holds;          // what it is for, as a word a test can select by (seats_taken, ...)
  const char* meaning;        // what the server keeps in it
  const char* capacity_rule;  // capacity(), in words
  // The capacity the server sets at start from --max-rooms and --max-players.
  std::uint64_t (*capacity)(std::uint32_t max_rooms, std::uint32_t max_players);
};

// Agones holds at most this many values in one List.
inline constexpr std::uint32_t kAgonesListMax = 1000;

// Rows of kFleetNames, by what the server keeps in them.
inline constexpr std::size_t kSeatsRow = 0, kRoomsRow = 1, kPlayersRow = 2, kFleetNameCount = 3;
extern const std::array<FleetName, kFleetNameCount> kFleetNames;

const char* to_string(FleetKind kind);  // "counter" or "list"
// The row of the Counter or List called `name`, if the server keeps one.
std::optional<std::size_t> fleet_row(FleetKind kind, std::string_view name);
// One JSON object per row and line: kind, name, holds, capacity (for these limits),
// meaning, capacity_rule (what --print-fleet-names prints).
std::string fleet_names_json_lines(std::uint32_t max_rooms, std::uint32_t max_players);

}  // namespace fts::server
