// The match step: joins and leaves, commands, phase changes; the playing tick itself is
// in match_play.cpp, levels and spawns in match_level.cpp.
#include "fts/sim/match.hpp"

#include <algorithm>
#include <optional>

#include "match_internal.hpp"

namespace fts::sim {

std::string_view to_string(Phase p) {
  switch (p) {
    case Phase::lobby: return "lobby";
    case Phase::playing: return "playing";
    case Phase::shop: return "shop";
    case Phase::game_over: return "game_over";
  }
  return "?";
}

std::string_view to_string(EventKind k) {
  switch (k) {
    case EventKind::joined: return "joined";
    case EventKind::join_refused: return "join_refused";
    case EventKind::left: return "left";
    case EventKind::level_started: return "level_started";
    case EventKind::enemy_defeated: return "enemy_defeated";
    case EventKind::player_fell: return "player_fell";
    case EventKind::player_respawned: return "player_respawned";
    case EventKind::level_complete: return "level_complete";
    case EventKind::purchase: return "purchase";
    case EventKind::rocket_fired: return "rocket_fired";
    case EventKind::game_over: return "game_over";
    case EventKind::interest: return "interest";
  }
  return "?";
}

std::string_view to_string(BodyKind k) {
  switch (k) {
    case BodyKind::enemy: return "enemy";
    case BodyKind::player: return "player";
    case BodyKind::rocket: return "rocket";
  }
  return "?";
}

Player* find_player(MatchState& s, PlayerId id) {
  auto it = std::lower_bound(s.players.begin(), s.players.end(), id,
                             [](const Player& p, PlayerId v) { return p.id < v; });
  return it != s.players.end() && it->id == id ? &*it : nullptr;
}
const Player* find_player(const MatchState& s, PlayerId id) {
  return find_player(const_cast<MatchState&>(s), id);
}
Ball* find_ball(World& w, BallId id) {
  auto it = std::lower_bound(w.balls.begin(), w.balls.end(), id,
                             [](const Ball& b, BallId v) { return b.id < v; });
  return it != w.balls.end() && it->id == id ? &*it : nullptr;
}
const Ball* find_ball(const World& w, BallId id) { return find_ball(const_cast<World&>(w), id); }

MatchState make_match(const MatchConfig& cfg, std::uint64_t seed) {
  MatchState s;
  s.cfg = cfg;
  s.rng = Rng(seed);
  s.world.arena.width_u = cfg.arena_width_u;
  s.world.arena.height_u = cfg.arena_height_u;
  s.world.arena.boundary = Boundary::open;
  s.physics = physics_settings(cfg);
  s.step_k = make_step_constants(s.physics, 1.0 / cfg.tick_rate_hz);
  return s;
}

namespace {

void handle_leaves(MatchState& s, std::vector<PlayerId> leaves, std::vector<Event>& out) {
  std::sort(leaves.begin(), leaves.end());
  leaves.erase(std::unique(leaves.begin(), leaves.end()), leaves.end());
  for (PlayerId id : leaves) {
    Player* p = find_player(s, id);
    if (!p) continue;
    if (p->ball) detail::remove_ball(s, p->ball);
    s.players.erase(s.players.begin() + (p - s.players.data()));
    // What names the player goes with it: its rockets, and every enemy's credit for its
    // touches (a fall after the leave credits nobody, issue 36).
    std::vector<BallId> rockets;
    for (auto& [ball, b] : s.bodies) {
      if (b.kind == BodyKind::rocket && b.owner == id) rockets.push_back(ball);
      if (b.credit == id) {
        b.credit = 0;
        b.credit_tick = -1;
      }
    }
    for (BallId ball : rockets) detail::remove_ball(s, ball);
    out.push_back(Left{id});
  }
}

// Players who hold a seat: everyone but those who quit (their progress waits for them).
std::int64_t seated_players(const MatchState& s) {
  return std::count_if(s.players.begin(), s.players.end(), [](const Player& p) { return !p.parked; });
}

// A name no other player of the match has: "ann", then "ann-2", "ann-3", ... (cut so
// that the whole stays within 16 characters).
std::string unique_name(const MatchState& s, const std::string& name) {
  auto taken = [&](const std::string& n) {
    return std::any_of(s.players.begin(), s.players.end(), [&](const Player& p) { return p.name == n; });
  };
  if (!taken(name)) return name;
  for (int i = 2;; ++i) {
    const std::string suffix = "-" + std::to_string(i);
    const std::string candidate = name.substr(0, 16 - std::min<std::size_t>(16, suffix.size())) + suffix;
    if (!taken(candidate)) return candidate;
  }
}

void handle_presence(MatchState& s, const TickInputs& in) {
  for (PlayerId id : in.away)
    if (Player* p = find_player(s, id)) p->connected = false;
  for (PlayerId id : in.quit) {
    Player* p = find_player(s, id);
    if (!p) continue;
    p->connected = false;
    p->parked = true;
    p->ready = false;
    p->respawn_tick = -1;
    if (p->ball) detail::remove_ball(s, p->ball);  // leaves the field; no life is lost
  }
  for (PlayerId id : in.back) {
    Player* p = find_player(s, id);
    if (!p) continue;
    p->connected = true;
    if (p->parked) {
      p->parked = false;
      if (s.phase == Phase::playing && p->in_match() && !p->ball) p->respawn_tick = s.tick;
    }
  }
}

// A join while a match runs (a new player: a reconnect with the session token comes back
// as TickInputs::back and keeps its own economy).
bool late_joiner(const MatchState& s) {
  return s.cfg.late_join_share > 0.0 && (s.phase == Phase::playing || s.phase == Phase::shop);
}

// README, "Where the rules left room": the total values of the players still in the
// match (away and parked ones too: their progress waits for them) set a newcomer's start.
Economy late_join_economy(const MatchState& s) {
  std::vector<Coins> values;
  for (const Player& q : s.players)
    if (q.in_match()) values.push_back(total_value(q.eco, s.cfg));
  return late_start_economy(s.levels_cleared, std::move(values), s.cfg);
}

void handle_joins(MatchState& s, std::vector<JoinRequest> joins, std::vector<Event>& out) {
  if (joins.empty()) return;
  std::stable_sort(joins.begin(), joins.end(), [](const auto& a, const auto& b) { return a.player < b.player; });
  // Every newcomer of a tick gets the same start, from the players there before it.
  const Economy start = late_joiner(s) ? late_join_economy(s) : start_economy(s.cfg);
  for (const JoinRequest& j : joins) {
    std::optional<JoinRefusal> refusal;
    if (j.player == 0) refusal = JoinRefusal::bad_id;
    else if (find_player(s, j.player)) refusal = JoinRefusal::id_in_use;
    else if (seated_players(s) >= s.cfg.max_players) refusal = JoinRefusal::match_full;
    else if (j.name.empty() || j.name.size() > 32) refusal = JoinRefusal::bad_name;
    if (refusal) {
      out.push_back(JoinRefused{j.player, *refusal});
      continue;
    }
    Player p;
    p.id = j.player;
    p.name = unique_name(s, j.name);
    p.eco = start;
    if (s.phase == Phase::game_over) p.eco.lives = 0;  // watches until "play again"
    auto at = std::lower_bound(s.players.begin(), s.players.end(), p.id,
                               [](const Player& q, PlayerId v) { return q.id < v; });
    const PlayerId id = p.id;
    s.players.insert(at, std::move(p));
    if (s.phase == Phase::playing) find_player(s, id)->respawn_tick = s.tick;
    out.push_back(Joined{id, j.name});
  }
}

CommandResult handle_command(MatchState& s, Player& p, const Command& c, std::vector<Event>& out) {
  CommandResult r;
  r.player = p.id;
  r.tag = c.tag;
  r.kind = c.kind;
  switch (c.kind) {
    case CommandKind::ready:
      if (accepts_ready(s, p)) p.ready = true;
      else r.code = Refusal::wrong_phase;
      return r;
    case CommandKind::play_again:
      if (accepts_play_again(s)) detail::start_new_match(s, out);
      else r.code = Refusal::wrong_phase;
      return r;
    case CommandKind::buy: break;
  }
  Purchased e;
  e.player = p.id;
  e.asked = c.item;
  e.coins_after = p.eco.coins;
  const auto item = parse_item(c.item);
  if (!item) {
    e.reason = Refusal::unknown_item;
  } else if (s.phase != Phase::shop || !p.in_match()) {
    e.item = *item;
    e.price = price_of(p.eco, *item);
    e.reason = Refusal::wrong_phase;
  } else {
    const Purchase bought = buy(p.eco, *item, s.level, s.cfg);
    e.item = bought.item;
    e.ok = bought.ok;
    e.reason = bought.reason;
    e.price = bought.price;
    e.coins_after = bought.coins_after;
  }
  out.push_back(e);
  r.code = e.reason;
  r.item = e.item;
  r.price = e.price;
  r.coins_after = e.coins_after;
  return r;
}

bool all_ready(const MatchState& s, bool only_in_match) {
  bool any = false;
  for (const Player& p : s.players) {
    if (only_in_match && !p.in_match()) continue;
    if (!p.connected) continue;
    any = true;
    if (!p.ready) return false;
  }
  return any;
}

bool any_ready(const MatchState& s) {
  return std::any_of(s.players.begin(), s.players.end(), [](const Player& p) { return p.connected && p.ready; });
}

}  // namespace

bool accepts_ready(const MatchState& s, const Player& p) {
  return s.phase == Phase::lobby || (s.phase == Phase::shop && p.in_match());
}

bool accepts_play_again(const MatchState& s) { return s.phase == Phase::game_over; }

TickOutput step(MatchState& s, const TickInputs& in) {
  TickOutput result;
  std::vector<Event>& out = result.events;
  handle_leaves(s, in.leaves, out);
  handle_joins(s, in.joins, out);
  handle_presence(s, in);

  std::vector<PlayerTick> inputs = in.players;
  std::stable_sort(inputs.begin(), inputs.end(), [](const auto& a, const auto& b) { return a.player < b.player; });
  for (const PlayerTick& t : inputs) {
    for (const Command& c : t.commands) {
      Player* p = find_player(s, t.player);  // re-found: a command may restart the match
      if (p) {
        result.results.push_back(handle_command(s, *p, c, out));
      } else {
        result.results.push_back({t.player, c.tag, c.kind, Refusal::no_player, Item::mass, 0, 0});
      }
    }
  }

  if (s.players.empty() && s.phase != Phase::lobby) {
    // Everyone left: back to an empty lobby.
    while (!s.world.balls.empty()) detail::remove_ball(s, s.world.balls.back().id);
    s.phase = Phase::lobby;
    s.level = 0;
  }
  switch (s.phase) {
    case Phase::lobby:
      if (all_ready(s, false)) {
        detail::start_new_match(s, out);
      } else if (!any_ready(s)) {
        s.lobby_deadline_tick = -1;
      } else if (s.lobby_deadline_tick < 0) {
        s.lobby_deadline_tick = s.tick + ticks_for(s.cfg, s.cfg.lobby_timeout_s);
      } else if (s.tick >= s.lobby_deadline_tick) {
        detail::start_new_match(s, out);
      }
      break;
    case Phase::shop:
      if (all_ready(s, true) || s.tick >= s.shop_deadline_tick) detail::start_level(s, s.level + 1, false, out);
      break;
    case Phase::playing:
    case Phase::game_over: break;
  }
  if (s.phase == Phase::playing) detail::play_tick(s, inputs, out);
  ++s.tick;
  return result;
}

}  // namespace fts::sim
