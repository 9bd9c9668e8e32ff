#include "app/careers.hpp"

#include <cstdio>
#include <random>

#include <nlohmann/json.hpp>

namespace fts::server {
namespace {

std::string random_key() {
  static thread_local std::random_device rd;
  char buf[33];
  std::snprintf(buf, sizeof buf, "%08x%08x%08x%08x", rd(), rd(), rd(), rd());
  return buf;
}

bool running(sim::Phase p) { return p == sim::Phase::playing || p == sim::Phase::shop; }

}  // namespace

void Careers::identify(std::uint32_t player, const std::string& identity, const std::string& name) {
  if (identity.empty()) return;
  who_[player] = {identity, name};
  if (auto it = tallies_.find(player); it != tallies_.end() && it->second.identity == identity) it->second.name = name;
}

void Careers::forget(const std::string& identity) {
  if (identity.empty()) return;
  std::erase_if(who_, [&](const auto& kv) { return kv.second.first == identity; });
  std::erase_if(tallies_, [&](const auto& kv) { return kv.second.identity == identity; });
}

const Tally* Careers::tally(std::uint32_t player) const {
  auto it = tallies_.find(player);
  return it == tallies_.end() ? nullptr : &it->second;
}

profiles::MatchResult Careers::finish(Tally& t, profiles::Ending ending, double tick_hz, std::int64_t unix_s) {
  t.done = true;
  profiles::MatchResult r;
  r.key = t.key;
  r.fingerprint = t.identity;
  r.name = t.name;
  r.ended_unix_s = unix_s;
  r.level = t.level;
  r.coins = t.coins;
  r.knocks = t.knocks;
  r.lives_lost = t.lives_lost;
  r.play_ms = tick_hz > 0 ? static_cast<std::int64_t>(static_cast<double>(t.play_ticks) * 1000.0 / tick_hz) : 0;
  r.ending = ending;
  return r;
}

std::vector<profiles::MatchResult> Careers::step(const sim::MatchState& m, const std::vector<sim::Event>& events,
                                                 std::int64_t unix_s, std::vector<std::uint32_t>* changed) {
  std::vector<profiles::MatchResult> out;
  const double hz = m.cfg.tick_rate_hz;
  auto live = [&](std::uint32_t p) -> Tally* {
    auto it = tallies_.find(p);
    return it == tallies_.end() || it->second.done ? nullptr : &it->second;
  };
  auto touched = [&](std::uint32_t p) {
    if (changed) changed->push_back(p);
  };
  bool game_over = false;
  for (const auto& e : events) {
    if (const auto* d = std::get_if<sim::EnemyDefeated>(&e)) {
      if (Tally* t = live(d->player.value)) ++t->knocks, touched(d->player.value);
    } else if (const auto* f = std::get_if<sim::PlayerFell>(&e)) {
      if (Tally* t = live(f->player.value)) ++t->lives_lost, touched(f->player.value);
    } else if (std::holds_alternative<sim::GameOver>(e)) {
      game_over = true;
    }
  }
  for (const sim::Player& p : m.players) {
    const std::uint32_t id = p.id.value;
    auto who = who_.find(id);
    if (who == who_.end()) continue;
    who->second.second = p.name;  // the name the match shows ("ann-2")
    Tally* t = live(id);
    if (t) t->name = p.name;
    if (!t && running(m.phase) && p.in_match()) {
      auto old = tallies_.find(id);
      // A new match of this player (the first, or one after its last ended).
      if (old == tallies_.end() || old->second.match != m.matches_started || old->second.identity != who->second.first) {
        Tally fresh;
        fresh.identity = who->second.first;
        fresh.name = who->second.second;
        fresh.key = new_key ? new_key() : random_key();
        fresh.match = m.matches_started;
        t = &(tallies_[id] = fresh);
        touched(id);
      }
    }
    if (!t) continue;
    if (m.phase == sim::Phase::playing && p.in_match() && m.level > t->level) t->level = m.level, touched(id);
    if (p.eco.coins > t->coins) t->coins = p.eco.coins;
    if (running(m.phase) && p.connected && !p.parked && p.in_match()) ++t->play_ticks;
    if (!p.in_match() || game_over) {
      out.push_back(finish(*t, profiles::Ending::game_over, hz, unix_s));
      touched(id);
    }
  }
  if (game_over) {  // players the match no longer lists
    for (auto& [id, t] : tallies_)
      if (!t.done) out.push_back(finish(t, profiles::Ending::game_over, hz, unix_s)), touched(id);
  }
  return out;
}

std::optional<profiles::MatchResult> Careers::released(std::uint32_t player, double tick_hz, std::int64_t unix_s) {
  who_.erase(player);
  auto it = tallies_.find(player);
  if (it == tallies_.end()) return std::nullopt;
  std::optional<profiles::MatchResult> r;
  if (!it->second.done) r = finish(it->second, profiles::Ending::quit, tick_hz, unix_s);
  tallies_.erase(it);
  return r;
}

std::vector<profiles::MatchResult> Careers::close(double tick_hz, std::int64_t unix_s) {
  std::vector<profiles::MatchResult> out;
  for (auto& [id, t] : tallies_)
    if (!t.done) out.push_back(finish(t, profiles::Ending::closed, tick_hz, unix_s));
  return out;
}

std::string Careers::saved(std::uint32_t player) const {
  const Tally* t = tally(player);
  if (!t) return "";
  nlohmann::json j = {{"key", t->key},       {"name", t->name},         {"match", t->match},
                      {"level", t->level},   {"coins", t->coins},       {"knocks", t->knocks},
                      {"lives_lost", t->lives_lost}, {"play_ticks", t->play_ticks}, {"done", t->done}};
  return j.dump();
}

void Careers::restore(std::uint32_t player, const std::string& identity, const std::string& saved) {
  if (identity.empty()) return;
  const auto j = nlohmann::json::parse(saved, nullptr, false);
  if (!j.is_object()) return;
  try {
    Tally t;
    t.identity = identity;
    t.key = j.at("key").get<std::string>();
    t.name = j.at("name").get<std::string>();
    t.match = j.at("match").get<std::int64_t>();
    t.level = j.at("level").get<std::int64_t>();
    t.coins = j.at("coins").get<std::int64_t>();
    t.knocks = j.at("knocks").get<std::int64_t>();
    t.lives_lost = j.at("lives_lost").get<std::int64_t>();
    t.play_ticks = j.at("play_ticks").get<std::int64_t>();
    t.done = j.at("done").get<bool>();
    if (t.key.size() != 32) return;
    tallies_[player] = t;
    who_[player] = {identity, t.name};
  } catch (const nlohmann::json::exception&) {
  }
}

}  // namespace fts::server
