// The Agones SDK's REST calls, without a socket (sans-I/O): the server says what it wants
// the sidecar to know (AgonesWanted), next() names the first call that is still owed, and
// done() records that the sidecar took it. The HTTP thread (agones_client) loops over
// next()/done(), so a failed call is simply owed again (retry; a Counter's or List's on
// its own backoff, failed(), while the other calls go on), and a burst of changes
// costs one call per difference, not one per change (the wanted state is one value, so
// this "queue" is bounded by construction). Paths and bodies as Agones documents them
// (agones.dev, "REST Game Server Client API").
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>

#include "fleet/fleet_names.hpp"
#include "fleet/fleet_state.hpp"
#include "fleet/update_retry.hpp"

namespace fts::server {

// The capacities the server sets at start, from its own limits (the rows' capacity()
// in fleet_names), so that the allocator's arithmetic holds whatever the manifest declared.
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
  std::optional<std::size_t> row;  // a Counter's or List's update: its row of kFleetNames
};

class AgonesSync {
 public:
  explicit AgonesSync(std::uint32_t update_retry_min_ms = UpdateRetry::kDefaultMinMs,
                      std::uint32_t update_retry_max_ms = UpdateRetry::kDefaultMaxMs);

  // The first call still owed to bring the sidecar to `wanted` at now_ms (the caller's
  // clock), in the order: capacities (seats Counter, rooms and players Lists), ready,
  // health, labels, the seats count, the rooms List, the players List (each List: removals
  // first, so it never holds more than its capacity), shutdown. A Counter or List whose
  // update failed is skipped until its retry is due (UpdateRetry), so Ready, Health and
  // Shutdown never wait on one the sidecar does not take. A List publishes the first
  // `capacity` values of the wanted ones (rooms in id order: an older room keeps its
  // place, a newer one waits for a free place); the others wait until one leaves.
  std::optional<SdkCall> next(const AgonesWanted& wanted, std::uint64_t now_ms = 0) const;
  // The sidecar took the call (2xx), or refused it for good (4xx: not retried); ends the
  // spell of its Counter or List.
  void done(const SdkCall& call);
  // The sidecar did not take a Counter's or List's update (a 5xx, which is what Agones
  // answers for one the GameServer does not declare, or no answer): tried again after
  // the row's backoff. True when the failure starts a spell. Only for calls with a row.
  bool failed(const SdkCall& call, std::uint64_t now_ms);
  const UpdateRetry& retry(std::size_t row) const { return retry_.at(row); }
  // The first time after now_ms when a failing Counter or List is due again (nullopt:
  // none is failing, or every failing one is due already).
  std::optional<std::uint64_t> next_retry_ms(std::uint64_t now_ms) const;

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
  std::array<UpdateRetry, kFleetNameCount> retry_;      // by row of kFleetNames
};

}  // namespace fts::server
