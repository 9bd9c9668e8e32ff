#include "ui/hud.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "fts/protocol/codes.hpp"
#include "fts/sim/shop_text.hpp"
#include "ui/sanitize.hpp"

namespace fts::client {

using protocol::EventKind;
using protocol::Phase;

const PlayerState* find_player(const Snapshot& s, std::uint32_t id) {
  for (const auto& p : s.players)
    if (p.id == id) return &p;
  return nullptr;
}

int protection_s(const PlayerState& p, const Snapshot& s, double tick_rate_hz) {
  if (p.protected_until_tick <= s.tick || tick_rate_hz <= 0) return -1;
  return static_cast<int>(std::ceil((p.protected_until_tick - s.tick) / tick_rate_hz));
}

std::string hud_line(const Snapshot& s, const ViewState& view) {
  const PlayerState* me = find_player(s, view.my_player_id);
  std::string out = "Level: " + std::to_string(s.level);
  if (me != nullptr) {
    out += "   Coins: " + sim::with_thousands(me->coins);
    out += "   Lives: " + std::to_string(me->lives);
    if (const int left = protection_s(*me, s, view.tick_rate_hz); left >= 0)
      out += "   Protected: " + std::to_string(left) + "s";
  }
  char buf[64];
  if (view.ping_ms >= 0) {
    std::snprintf(buf, sizeof buf, "   Ping: %.0f ms", view.ping_ms);
    out += buf;
  }
  if (view.loss_percent >= 0) {
    std::snprintf(buf, sizeof buf, "   Loss: %.1f%%", view.loss_percent);
    out += buf;
  }
  if (view.delay_ms >= 0) out += "   Delay: " + std::to_string(view.delay_ms) + " ms";  // the jitter buffer's
  if (!view.room.empty()) out += "   " + view.room;  // last: the fields before keep their place
  return out;
}

namespace {

std::string plural(std::int64_t n, const char* one, const char* many) {
  return sim::with_thousands(n) + " " + (n == 1 ? one : many);
}

std::string name_of(const Snapshot& s, std::uint32_t id, const std::map<std::uint32_t, std::string>* names) {
  const PlayerState* p = find_player(s, id);
  if (p != nullptr) return sanitize(p->name, 16);
  if (names != nullptr)
    if (const auto it = names->find(id); it != names->end()) return sanitize(it->second, 16);
  return "player " + std::to_string(id);
}

}  // namespace

std::string players_line(const Snapshot& s, const ViewState& view) {
  std::string out = "Players:";
  bool first = true;
  for (const auto& p : s.players) {
    out += first ? " " : " | ";
    first = false;
    out += sanitize(p.name, 16);
    if (p.id == view.my_player_id) out += " (you)";
    out += " " + plural(p.coins, "coin", "coins") + " " + plural(p.lives, "life", "lives");
    if (p.lives <= 0 && !p.alive) out += " out";
  }
  return out;
}

sim::Economy economy_of(const PlayerState& p) {
  sim::Economy e;
  e.coins = p.coins;
  e.lives = p.lives;
  e.mass = std::isfinite(p.mass) ? std::llround(std::clamp(p.mass, 0.0, 1e15)) : 0;
  e.vmax_u_per_s = p.vmax_u_per_s;
  e.accel_u_per_s2 = p.accel_u_per_s2;
  e.multiplier = p.multiplier;
  e.bank = p.bank;
  e.rockets = p.weapon == protocol::Weapon::rockets;
  for (const sim::ItemDef& d : sim::item_table()) e.prices[d.item] = static_cast<double>(p.prices[sim::index_of(d.item)]);
  return e;
}

std::vector<std::string> shop_screen_lines(const PlayerState& p, std::uint32_t level, const sim::ShopTerms& terms) {
  return sim::shop_lines(economy_of(p), level, terms);
}

int countdown_s(const Snapshot& s, double tick_rate_hz) {
  if (s.deadline_tick == 0 || tick_rate_hz <= 0) return -1;
  if (s.deadline_tick <= s.tick) return 0;
  return static_cast<int>((s.deadline_tick - s.tick + tick_rate_hz - 1) / tick_rate_hz);
}

std::string ready_line(const Snapshot& s) {
  std::string out = "Ready:";
  bool first = true;
  for (const auto& p : s.players) {
    if (p.lives <= 0 && !p.alive) continue;
    out += first ? " " : ", ";
    first = false;
    out += sanitize(p.name, 16) + (p.ready ? " (ready)" : s.phase == Phase::shop ? " (shopping)" : " (not ready)");
  }
  return out;
}

std::string help_line(Phase phase) {
  switch (phase) {
    case Phase::play:
      return "Move: arrows/WASD/hjkl/mouse   Fire rockets: space   Chat: t   Quit: q";
    case Phase::shop: {
      std::string line = "Buy:";
      for (const sim::ItemDef& d : sim::item_table()) (line += ' ') += d.key;
      return line + "   Ready: Enter   Chat: t   Quit: q";
    }
    case Phase::over:
      return "Game over   Play again: Enter   Chat: t   Quit: q";
    case Phase::lobby:
      return "Waiting for the match   Ready: Enter   Chat: t   Quit: q";
  }
  return "Quit: q";
}

namespace {

std::string item_name(std::uint32_t key) {
  const auto item = key < 0x80 ? sim::item_by_key(static_cast<char>(key)) : std::nullopt;
  return item ? std::string(sim::item_def(*item).name) : "an item";
}

}  // namespace

std::string refusal_text(const std::string& code, const std::string& server_message, char item, const PlayerState* me) {
  const sim::ItemDef* def = nullptr;
  for (const sim::ItemDef& d : sim::item_table())
    if (item != 0 && d.key == item) def = &d;
  const std::string what = def != nullptr ? std::string(def->name) : std::string("that");
  using protocol::ResultCode;
  const ResultCode rc = protocol::result_code_of(code).value_or(ResultCode::count_);
  switch (rc) {
    case ResultCode::coins:
      if (me != nullptr && def != nullptr)
        return "not enough coins: " + what + " costs " + sim::with_thousands(me->prices[sim::index_of(def->item)]) +
               ", you have " + sim::with_thousands(me->coins);
      return "not enough coins";
    case ResultCode::owned: return "you already have " + what + ": it is bought once";
    case ResultCode::phase:
      // Out of lives, the shop is closed to us while it is open to the others (issue 26).
      if (me != nullptr && me->lives <= 0) return "you are out of lives: you play again when this match ends";
      return "not now: the shop is closed";
    case ResultCode::dead: return "you are out of the match: watching";
    case ResultCode::item: return "there is no such item in the shop";
    case ResultCode::op: return "this server does not know that command";
    case ResultCode::rate:
    case ResultCode::empty:
    case ResultCode::busy:
    case ResultCode::no_profiles:
    case ResultCode::unavailable:
    case ResultCode::guest: return std::string(protocol::result_sentence(rc));
    case ResultCode::ok:
    case ResultCode::field:
    case ResultCode::spectator:
    case ResultCode::count_: break;  // the server's sentence says it
  }
  const std::string msg = sanitize(server_message, 120);
  return msg.empty() ? "refused (" + sanitize(code, 32) + ")" : msg;
}

std::string describe_event(const protocol::Event& e, const Snapshot& s, std::uint32_t my_id,
                           const std::map<std::uint32_t, std::string>* names) {
  const auto who = [&](std::uint32_t id) { return id == my_id ? std::string("You") : name_of(s, id, names); };
  switch (e.kind) {
    case EventKind::enemy_fell:
      if (e.b == 0) return "An enemy fell off.";
      return who(e.b) + " knocked an enemy off: +" + sim::with_thousands(e.value) + " coins.";
    case EventKind::player_fell:
      return who(e.a) + " fell off (" + plural(e.value, "life", "lives") + " left).";
    case EventKind::level_started: return "Level " + std::to_string(e.value) + " started.";
    case EventKind::level_complete: return "Level " + std::to_string(e.value) + " Complete";
    case EventKind::purchase:
      return who(e.a) + " bought " + item_name(e.b) + " for " +
             sim::with_thousands(e.value) + " coins.";
    case EventKind::player_joined: return who(e.a) + " joined.";
    case EventKind::player_left: return who(e.a) + " left.";
    case EventKind::rocket_fired: return who(e.a) + " fired a rocket.";
    case EventKind::match_over:
      return "Game over at level " + std::to_string(e.value) + ".";
    case EventKind::respawned: return who(e.a) + " respawned.";
    case EventKind::interest:
      return who(e.a) + " earned " + sim::with_thousands(e.value) + " coins of interest.";
    case EventKind::level_restarted: return "Level " + std::to_string(e.value) + " restarts.";
    case EventKind::count_: break;
  }
  return {};
}

}  // namespace fts::client
