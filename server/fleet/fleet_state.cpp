#include "fleet/fleet_state.hpp"

#include "app/game_host.hpp"

namespace fts::server {

FleetState observe(const GameHost& host) {
  FleetState s;
  for (const auto& session : host.endpoint().sessions())
    if (session.connected) s.players.insert(session.name);
  // A seat is what admission counts (ServerEndpoint::seats_in_room): a player's, connected
  // or away with the slot held for a reconnect, so the Counter's free seats are the joins
  // the server would take.
  for (const auto id : host.room_ids()) {
    const Room* r = host.room(id);
    s.room_codes.push_back(r->code());
    s.seats += static_cast<std::uint32_t>(host.endpoint().seats_in_room(id));
  }
  s.rooms = static_cast<std::uint32_t>(s.room_codes.size());
  s.draining = host.draining();
  s.phase = s.draining ? "draining" : std::string(sim::to_string(host.match().phase));
  return s;
}

}  // namespace fts::server
