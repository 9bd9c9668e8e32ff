// The Agones SDK's REST calls, without a socket (sans-I/O): the server says what it wants
// the sidecar to know (AgonesWanted), next() names the first call that is still owed, and
// done() records that the sidecar took it. The HTTP thread (agones_client) loops over
// next()/done(), so a failed call is simply owed again (retry), and a burst of changes
// costs one call per difference, not one per change (the wanted state is one value, so
// this "queue" is bounded by construction). Paths and bodies as Agones documents them
// (agones.dev, "REST Game Server Client API").
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "fleet/fleet_state.hpp"

namespace fts::server {

// The names used in the manifests (docker/agones/): Counter "seats", Lists "rooms" and
// "players", labels agones.dev/sdk-version and agones.dev/sdk-phase. A GameServerAllocation
// selects by them: seats minAvailable (free seats) for quick play, rooms containsValue
// for "join code X".
inline constexpr const char* kSeatsCounter = "seats";
inline constexpr const char* kRoomsList = "rooms";
inline constexpr const char* kPlayersList = "players";
// Agones holds at most this many values in one List.
inline constexpr std::uint32_t kAgonesListMax = 1000;

// The capacities the server sets at start, from its own limits, so that the allocator's
// arithmetic holds whatever the manifest declared: seats = max_rooms x max_players (count =
// seats taken, so minAvailable = free seats), rooms = max_rooms, players = the seats; each
// List at most kAgonesListMax.
struct AgonesCapacity {
  std::uint64_t seats = 64 * 8;
  std::uint32_t rooms = 64;
  std::uint32_t players = 64 * 8;
};
AgonesCapacity agones_capacity(std::uint32_t max_rooms, std::uint32_t max_players);

struct AgonesWanted {
  bool ready = false;            // the port is bound: players and rooms can come
  std::uint64_t health_seq = 0;  // bumped by the tick loop once per health period
  FleetState state;
  std::string version;
  AgonesCapacity capacity;
  bool shutdown = false;         // the drain is over
};

enum class SdkOp { counter_capacity, list_capacity, ready, health, label, counter, list_remove, list_add, shutdown };

struct SdkCall {
  SdkOp op = SdkOp::ready;
  std::string method, path, body;
  std::string key, value;      // label key and value; list name and value
  std::uint64_t number = 0;    // counter count or capacity; list capacity; health seq
};

class AgonesSync {
 public:
  // The first call still owed to bring the sidecar to `wanted`, in the order: capacities
  // (seats Counter, rooms and players Lists), ready, health, labels, the seats count, the
  // rooms List, the players List (each List: removals first, so it never holds more than
  // its capacity), shutdown. A List publishes the first `capacity` values of the wanted
  // ones (rooms in id order: an older room keeps its place, a newer one waits for a free
  // place); the others are not published until one leaves.
  std::optional<SdkCall> next(const AgonesWanted& wanted) const;
  // The sidecar took the call (2xx), or refused it for good (4xx: not retried).
  void done(const SdkCall& call);

  bool shutdown_sent() const { return shutdown_; }
  bool ready_sent() const { return ready_; }

 private:
  bool ready_ = false;
  bool shutdown_ = false;
  std::uint64_t health_seq_ = 0;
  std::map<std::string, std::string> labels_;
  std::optional<std::uint64_t> seats_capacity_;
  std::optional<std::uint64_t> seats_;
  std::map<std::string, std::uint64_t> list_capacity_;  // by list name
  std::map<std::string, std::set<std::string>> lists_;  // by list name: the values the sidecar holds
};

}  // namespace fts::server
