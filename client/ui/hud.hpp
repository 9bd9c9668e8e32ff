// The text parts of the screen: the HUD line in the original's words, the player list,
// the shop screen of the seed's slide, and the help line of controls.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fts/protocol/snapshot.hpp"
#include "fts/sim/economy.hpp"
#include "ui/view.hpp"

namespace fts::client {

using protocol::PlayerState;
using protocol::Snapshot;

// The player with this id, or nullptr.
const PlayerState* find_player(const Snapshot& s, std::uint32_t id);

// Whole seconds of spawn protection the player's ball has left (rounded up), or -1 when
// it is not protected.
int protection_s(const PlayerState& p, const Snapshot& s, double tick_rate_hz);
// "Level: 3   Coins: 286   Lives: 1   Protected: 3s   Ping: 23 ms   Loss: 0.0%" (the
// protection only while the own ball has it).
std::string hud_line(const Snapshot& s, const ViewState& view);
// "Players: ann 286 coins 1 life | bob 12 coins 3 lives" (names sanitised).
std::string players_line(const Snapshot& s, const ViewState& view);
// A player's public state as the shop text's economy.
sim::Economy economy_of(const PlayerState& p);
// The seed's shop screen for this player after `level` (common's shop_lines), stating
// the server's terms (from its welcome).
std::vector<std::string> shop_screen_lines(const PlayerState& p, std::uint32_t level,
                                           const sim::ShopTerms& terms = {});
// "Ready: ann (ready), bob (shopping)".
// Whole seconds until the snapshot's lobby/shop deadline (rounded up), or -1 when no
// countdown runs.
int countdown_s(const protocol::Snapshot& s, double tick_rate_hz);

std::string ready_line(const Snapshot& s);
// Controls for the phase.
std::string help_line(protocol::Phase phase);
// "Bought mass for 35 coins." for a purchase event. `names` gives the names of players no
// longer in the snapshot (one who left).
std::string describe_event(const protocol::Event& e, const Snapshot& s, std::uint32_t my_id,
                           const std::map<std::uint32_t, std::string>* names = nullptr);
// A refused command in words: "not enough coins: mass costs 35, you have 12" for code
// "coins"; `me` (may be null) gives the price and the coins; `item` is the buy's key.
std::string refusal_text(const std::string& code, const std::string& server_message, char item,
                         const PlayerState* me);

}  // namespace fts::client
