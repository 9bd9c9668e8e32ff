#include "fts/room/match_config_json.hpp"

#include <cmath>
#include <type_traits>
#include <variant>

#include "fts/room/json_fields.hpp"
#include "fts/sim/config_fields.hpp"

namespace fts::room {
namespace {

using sim::MatchConfig;

// The value of `key` into its member of cfg, by the member's type; false: no such key.
bool read_config_key(const Fields& f, const std::string& key, const nlohmann::json& value, MatchConfig& cfg) {
  bool found = false;
  fields::for_each(sim::kMatchConfigFields, [&](const auto& row) {
    if (found || key != row.key) return;
    found = true;
    auto& v = cfg.*row.member;
    using T = std::remove_cvref_t<decltype(v)>;
    if constexpr (std::is_same_v<T, double>) {
      v = f.number(key);
    } else if constexpr (std::is_same_v<T, sim::Model>) {
      const std::string s = f.string(key);
      const auto m = sim::parse_model(s);
      if (!m) f.fail(key, "must be one of seed, discrete, continuous, got \"" + s + "\"");
      v = *m;
    } else if constexpr (std::is_same_v<T, int>) {
      const std::int64_t n = f.integer(key);
      if (n < INT32_MIN || n > INT32_MAX) f.fail(key, "out of range, got " + value.dump());
      v = static_cast<int>(n);
    } else {
      static_assert(std::is_same_v<T, std::int64_t>, "a reader for this type of config field");
      v = f.integer(key);
    }
  });
  return found;
}

}  // namespace

std::variant<sim::MatchConfig, std::string> parse_match_config(const std::string& text, const sim::MatchConfig& base) {
  std::string why;
  const auto parsed = parse_json(text, why);
  if (!parsed) return "match config: invalid JSON: " + why;
  const nlohmann::json& j = *parsed;
  try {
    Fields f(j, "");
    MatchConfig cfg = base;
    for (const auto& item : j.items()) {
      // Named, not bound: clang before 16 cannot capture a structured binding.
      const std::string& key = item.key();
      const nlohmann::json& value = item.value();
      if (!read_config_key(f, key, value, cfg)) f.fail(key, "unknown key (value " + value.dump() + ")");
    }
    if (const std::string err = sim::validate(cfg); !err.empty()) return "match config: " + err;
    return cfg;
  } catch (const FieldError& e) {
    return std::string("match config: ") + e.what();
  }
}

nlohmann::json match_config_to_json(const sim::MatchConfig& cfg) {
  nlohmann::json j = nlohmann::json::object();
  fields::for_each(sim::kMatchConfigFields, [&](const auto& row) {
    const auto& v = cfg.*row.member;
    if constexpr (std::is_same_v<std::remove_cvref_t<decltype(v)>, sim::Model>) j[std::string(row.key)] = std::string(sim::to_string(v));
    else j[std::string(row.key)] = v;
  });
  return j;
}

std::vector<std::string> match_config_client_keys() {
  std::vector<std::string> out;
  fields::for_each(sim::kMatchConfigFields, [&](const auto& row) {
    if (sim::is_client_key<decltype(row.kind)>) out.emplace_back(row.key);
  });
  return out;
}

std::string to_input_line(std::int64_t tick, const sim::TickInputs& in) {
  nlohmann::json j = {{"tick", tick}};
  if (!in.joins.empty()) {
    auto& a = j["joins"] = nlohmann::json::array();
    for (const auto& jr : in.joins) a.push_back({{"player", jr.player}, {"name", jr.name}});
  }
  if (!in.leaves.empty()) j["leaves"] = in.leaves;
  if (!in.away.empty()) j["away"] = in.away;
  if (!in.back.empty()) j["back"] = in.back;
  if (!in.quit.empty()) j["quit"] = in.quit;
  if (!in.players.empty()) {
    auto& a = j["players"] = nlohmann::json::array();
    for (const auto& p : in.players) {
      nlohmann::json o = {{"id", p.player}};
      if (p.input.move_x) o["x"] = p.input.move_x;
      if (p.input.move_y) o["y"] = p.input.move_y;
      if (p.input.fire) o["fire"] = true;
      if (!p.commands.empty()) {
        auto& c = o["cmd"] = nlohmann::json::array();
        for (const auto& cmd : p.commands) {
          switch (cmd.kind) {
            case sim::CommandKind::buy: c.push_back("buy:" + cmd.item); break;
            case sim::CommandKind::ready: c.push_back("ready"); break;
            case sim::CommandKind::play_again: c.push_back("play_again"); break;
          }
        }
      }
      a.push_back(std::move(o));
    }
  }
  return j.dump();
}

namespace {

std::uint32_t player_id(const Fields& f, std::string_view key) {
  const std::int64_t v = f.integer(key);
  if (v < 1 || v > UINT32_MAX) f.fail(key, "must be a player id 1..4294967295, got " + std::to_string(v));
  return static_cast<std::uint32_t>(v);
}

std::int8_t axis(const Fields& f, std::string_view key) {
  const std::int64_t v = f.integer_or(key, 0);
  if (v < -1 || v > 1) f.fail(key, "must be -1, 0 or 1, got " + std::to_string(v));
  return static_cast<std::int8_t>(v);
}

}  // namespace

std::variant<InputLine, std::string> parse_input_line(const std::string& line) {
  std::string why;
  const auto parsed = parse_json(line, why);
  if (!parsed) return "input line: invalid JSON: " + why;
  return input_line_from_json(*parsed);
}

std::variant<InputLine, std::string> input_line_from_json(const nlohmann::json& j) {
  try {
    Fields f(j, "");
    f.only({"tick", "joins", "leaves", "away", "back", "quit", "players"});
    InputLine out;
    out.tick = f.integer("tick");
    if (out.tick < 0) f.fail("tick", "must be >= 0, got " + std::to_string(out.tick));
    auto list = [&](std::string_view key) -> const nlohmann::json* {
      if (!f.has(key)) return nullptr;
      const auto& a = f.at(key);
      if (!a.is_array()) f.fail(key, "must be an array, got " + a.dump());
      return &a;
    };
    if (const auto* a = list("joins")) {
      for (std::size_t i = 0; i < a->size(); ++i) {
        Fields g((*a)[i], "joins[" + std::to_string(i) + "]");
        g.only({"player", "name"});
        out.inputs.joins.push_back({player_id(g, "player"), g.string("name")});
      }
    }
    for (auto [key, dest] : {std::pair{"leaves", &out.inputs.leaves}, std::pair{"away", &out.inputs.away},
                             std::pair{"back", &out.inputs.back}, std::pair{"quit", &out.inputs.quit}}) {
      const auto* a = list(key);
      if (!a) continue;
      for (std::size_t i = 0; i < a->size(); ++i) {
        const auto& v = (*a)[i];
        if (!v.is_number_unsigned() || v.get<std::uint64_t>() < 1 || v.get<std::uint64_t>() > UINT32_MAX)
          f.fail(key, "must hold player ids, got " + v.dump());
        dest->push_back(v.get<std::uint32_t>());
      }
    }
    if (const auto* a = list("players")) {
      for (std::size_t i = 0; i < a->size(); ++i) {
        Fields g((*a)[i], "players[" + std::to_string(i) + "]");
        g.only({"id", "x", "y", "fire", "cmd"});
        sim::PlayerTick t;
        t.player = player_id(g, "id");
        t.input.move_x = axis(g, "x");
        t.input.move_y = axis(g, "y");
        t.input.fire = g.boolean_or("fire", false);
        if (g.has("cmd")) {
          const auto& c = g.at("cmd");
          if (!c.is_array()) g.fail("cmd", "must be an array, got " + c.dump());
          for (const auto& v : c) {
            if (!v.is_string()) g.fail("cmd", "must hold strings, got " + v.dump());
            const std::string s = v.get<std::string>();
            if (s == "ready") t.commands.push_back({sim::CommandKind::ready, {}});
            else if (s == "play_again") t.commands.push_back({sim::CommandKind::play_again, {}});
            else if (s.rfind("buy:", 0) == 0) t.commands.push_back({sim::CommandKind::buy, s.substr(4)});
            else g.fail("cmd", "unknown command \"" + s + "\" (ready, play_again, buy:ITEM)");
          }
        }
        out.inputs.players.push_back(std::move(t));
      }
    }
    return out;
  } catch (const FieldError& e) {
    return std::string("input line: ") + e.what();
  }
}

}  // namespace fts::room
