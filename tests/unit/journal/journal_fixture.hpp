// What the journal's unit tests share: a temporary directory, a match stepped and
// journaled as the host does it (with the live hash and event number of every tick),
// and line-level reading and writing of segment files.
#pragma once

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "../../support/temp_dir.hpp"
#include "store/journal.hpp"
#include "fts/room/snapshot_build.hpp"

namespace fts::test {

// The wire events of a step, numbered as the server's rooms number them (fts_room).
inline std::uint32_t count_events(std::int64_t tick, const sim::TickOutput& out) {
  std::vector<protocol::Event> wire;
  room::append_wire_events(tick + 1, out.events, wire);
  return static_cast<std::uint32_t>(wire.size());
}

// Two players join, get ready and play with a fixed pattern of keys and purchases.
inline sim::TickInputs inputs_at(std::int64_t tick) {
  sim::TickInputs in;
  for (std::uint32_t id = 1; id <= 2; ++id) {
    if (tick == 0) in.joins.push_back({id, id == 1 ? "ann" : "hash"});
    sim::PlayerTick t;
    t.player = id;
    t.input.move_x = static_cast<std::int8_t>((tick / 37 + id) % 3 - 1);
    t.input.move_y = static_cast<std::int8_t>((tick / 53 + id) % 3 - 1);
    t.input.fire = tick % 41 == 0;
    if (tick == 1) t.commands.push_back({sim::CommandKind::ready, {}, 0});
    if (tick % 300 == 150) t.commands.push_back({sim::CommandKind::buy, "mass", 0});
    in.players.push_back(t);
  }
  return in;
}

// A match stepped as the host steps it, journaled; the live hash of every tick kept.
struct Played {
  sim::MatchConfig cfg;
  sim::MatchState state = sim::make_match(cfg, 7);
  std::uint32_t event_seq = 0;
  std::map<std::int64_t, std::uint64_t> hash_at;  // state.tick -> match_hash
  std::map<std::int64_t, std::uint32_t> seq_at;

  void play(store::JournalWriter& w, std::int64_t ticks) {
    for (std::int64_t i = 0; i < ticks; ++i) {
      const auto in = inputs_at(state.tick);
      if (state.tick == 0) {
        w.session(0, {1, "ann", std::string(32, 'a'), false});
        w.session(0, {2, "hash", std::string(32, 'b'), false});
      }
      w.inputs(state.tick, in);
      const std::int64_t before = state.tick;
      event_seq += count_events(before, sim::step(state, in));
      w.stepped(state, event_seq);
      hash_at[state.tick] = sim::match_hash(state);
      seq_at[state.tick] = event_seq;
    }
  }
};

inline store::JournalConfig config_in(const std::filesystem::path& dir, std::int64_t checkpoint_every) {
  store::JournalConfig c;
  c.dir = dir;
  c.room = "main";
  c.version = "test";
  c.seed = 7;
  c.sync_ms = 5;
  c.checkpoint_every_ticks = checkpoint_every;
  return c;
}

inline store::ResumedRoom read_ok(const std::filesystem::path& dir) {
  auto r = store::read_journal(dir);
  if (auto* err = std::get_if<std::string>(&r)) FAIL(*err);
  return std::get<store::ResumedRoom>(std::move(r));
}

inline std::vector<std::string> lines_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::vector<std::string> out;
  for (std::string line; std::getline(in, line);) out.push_back(line);
  return out;
}

inline void write_lines(const std::filesystem::path& file, const std::vector<std::string>& lines, bool last_newline = true) {
  std::ofstream out(file, std::ios::trunc);
  for (std::size_t i = 0; i < lines.size(); ++i) out << lines[i] << (i + 1 < lines.size() || last_newline ? "\n" : "");
}

}  // namespace fts::test
