#include "app/admission.hpp"

#include "app/game_host.hpp"

namespace fts::server {
namespace {

protocol::Admission refusal(protocol::ErrorCode code, std::string message) {
  protocol::Admission a;
  a.error = code;
  a.message = std::move(message);
  return a;
}

}  // namespace

void apply_address_limits(protocol::ServerConfig& c, std::uint32_t max_per_address) {
  // The seats one host may hold (the endpoint refuses the next with address_full).
  c.max_sessions_per_address = max_per_address;
  // A host may send what its sessions may send together...
  c.address_datagrams_per_s = c.address_datagram_burst = c.session_datagrams_per_s * max_per_address;
  // ... and may shake hands as often as it may seat players (never under the default 10/s).
  c.hellos_per_s = c.hello_burst = std::max<std::uint32_t>(c.hellos_per_s, max_per_address);
}

// Called by the endpoint for a new player whose hello passed every other check.
protocol::Admission GameHost::admit(const protocol::JoinAsk& ask) {
  const std::string& how = ask.join;
  auto admitted = [&](const Room& r, bool spectator) {
    protocol::Admission a;
    a.room = r.id();
    a.code = r.code();
    a.spectator = spectator;
    a.server_tick = static_cast<std::uint32_t>(r.match().tick);
    return a;
  };
  if (refuse_players_) {
    log_record(spdlog::level::info, "join_refused", {{"address", ask.from}, {"reason", protocol::to_string(protocol::ErrorCode::draining)}});
    return refusal(protocol::ErrorCode::draining, "this server is shutting down; join another");
  }
  auto new_room = [&](bool is_private) -> protocol::Admission {
    if (draining_) return refusal(protocol::ErrorCode::server_full, "the server is draining (about to restart): no new rooms");
    // A host's open rooms are counted against it; its own empty ones make way first.
    const std::string maker(protocol::host_of(ask.from));
    if (rooms_made_by(maker) >= options_.max_rooms_per_host && !reclaim_room(&maker, now_ms_))
      return refusal(protocol::ErrorCode::address_full, "this address has made " + std::to_string(options_.max_rooms_per_host) +
                                                   " rooms that are still open (the most one address may); join one by its code");
    // Never refused while a room that holds nobody could be closed: the longest empty goes.
    if (rooms_.size() >= options_.max_rooms && !reclaim_room(nullptr, now_ms_))
      return refusal(protocol::ErrorCode::server_full, "the server has " + std::to_string(options_.max_rooms) +
                                        " rooms already, all full; try again later");
    Room* r = create_room(is_private, maker);
    if (!r) return refusal(protocol::ErrorCode::server_full, "no room code is free");
    return admitted(*r, false);
  };
  if (how.empty() || how == "quick") {
    // The public room in the lobby or the shop with the most players and a free seat
    // (the lowest id among equals), else a new one.
    const Room* best = nullptr;
    std::size_t best_seats = 0;
    for (const auto& [id, r] : rooms_) {
      if (r->is_private() || r->unconfirmed_until_ms != 0) continue;  // private, or perhaps not staying
      const auto phase = r->match().phase;
      if (phase != sim::Phase::lobby && phase != sim::Phase::shop) continue;
      const std::size_t seats = endpoint_.seats_in_room(id);
      if (seats >= options_.max_players) continue;
      if (!best || seats > best_seats) {
        best = r.get();
        best_seats = seats;
      }
    }
    if (best) return admitted(*best, false);
    return new_room(false);
  }
  if (how == "create") return new_room(true);
  if (how == "join" || how == "spectate") {
    const auto code = normalize_room_code(ask.room);
    if (!code) return refusal(protocol::ErrorCode::no_such_room, "a room code is 5 letters (A-Z without I, L, O)");
    const Room* r = room_by_code(*code);
    if (!r) return refusal(protocol::ErrorCode::no_such_room, "there is no room " + *code + " on this server");
    // Adopted and not yet confirmed by its server (GameHost::confirm_adopted): it may stay there.
    // (Not no_such_room: the code is right, and must not count as a guess.)
    if (r->unconfirmed_until_ms != 0)
      return refusal(protocol::ErrorCode::room_full, "room " + *code + " is still moving here; try again in a moment");
    if (how == "join") {
      if (endpoint_.seats_in_room(r->id()) >= options_.max_players)
        return refusal(protocol::ErrorCode::room_full, "room " + *code + " has all " + std::to_string(options_.max_players) +
                                        " seats taken; spectate it or try again later");
      return admitted(*r, false);
    }
    if (endpoint_.spectators_in_room(r->id()) >= options_.max_spectators)
      return refusal(protocol::ErrorCode::room_full, "room " + *code + " has " + std::to_string(options_.max_spectators) +
                                      " spectators already (the most it takes)");
    return admitted(*r, true);
  }
  return refusal(protocol::ErrorCode::bad_join, "join must be quick, create, join or spectate");
}

}  // namespace fts::server
