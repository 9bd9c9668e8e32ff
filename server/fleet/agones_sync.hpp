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

struct AgonesWanted {
  bool ready = false;            // the port is bound: players and rooms can come
  std::uint64_t health_seq = 0;  // bumped by the tick loop once per health period
  FleetState state;
  std::string version;
  bool shutdown = false;         // the drain is over
};

enum class SdkOp { ready, health, label, counter, list_remove, list_add, shutdown };

struct SdkCall {
  SdkOp op = SdkOp::ready;
  std::string method, path, body;
  std::string key, value;      // label key and value; list value
  std::uint64_t number = 0;    // counter count; health seq
};

// The names used in the manifests (docker/agones/): Counter "rooms", List "players",
// labels agones.dev/sdk-version and agones.dev/sdk-phase.
inline constexpr const char* kRoomsCounter = "rooms";
inline constexpr const char* kPlayersList = "players";

class AgonesSync {
 public:
  // The first call still owed to bring the sidecar to `wanted`, in the order ready,
  // health, labels, rooms counter, players list (removals first), shutdown.
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
  std::optional<std::uint64_t> rooms_;
  std::set<std::string> players_;
};

}  // namespace fts::server
