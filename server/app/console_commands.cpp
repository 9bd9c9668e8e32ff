#include "app/console_commands.hpp"

#include <algorithm>
#include <optional>

#include "app/game_host.hpp"
#include "app/room_codes.hpp"
#include "fts/protocol/limits.hpp"
#include "fts/room/json_fields.hpp"
#include "fts/room/text.hpp"

namespace fts::server {
namespace {

using Reply = nlohmann::ordered_json;
using Words = std::span<const std::string>;

Reply error_reply(const std::string& message) {
  Reply j;
  j["ok"] = false;
  j["error"] = message;
  return j;
}

Reply ok_reply() {
  Reply j;
  j["ok"] = true;
  return j;
}

// A field that is an unsigned number up to 2^32 - 1, else nothing.
std::optional<std::uint32_t> u32_of(const nlohmann::json& req, const char* key) {
  if (!req.contains(key) || !req[key].is_number_unsigned() || req[key].get<std::uint64_t>() > 0xFFFFFFFFull)
    return std::nullopt;
  return static_cast<std::uint32_t>(req[key].get<std::uint64_t>());
}

// A room by code ("ABCDE", any case) or id (3).
const Room* find_room(const GameHost& host, const nlohmann::json& v) {
  if (v.is_number_unsigned())
    return v.get<std::uint64_t>() > 0xFFFFFFFFull ? nullptr : host.room(static_cast<std::uint32_t>(v.get<std::uint64_t>()));
  if (v.is_string())
    if (auto code = normalize_room_code(v.get<std::string>())) return host.room_by_code(*code);
  return nullptr;
}

Reply room_json(const GameHost& host, const Room& r) {
  Reply j;
  j["id"] = r.id();
  j["code"] = r.code();
  j["private"] = r.is_private();
  j["players"] = host.endpoint().seats_in_room(r.id());
  j["spectators"] = host.endpoint().spectators_in_room(r.id());
  j["level"] = r.match().level;
  j["phase"] = std::string(sim::to_string(r.match().phase));
  j["tick"] = r.match().tick;
  j["seed"] = r.seed();
  j["state_hash"] = room::hex16(sim::match_hash(r.match()));
  return j;
}

// ---- handlers -----------------------------------------------------------------------

Reply rooms(GameHost& host, const nlohmann::json&, std::uint64_t) {
  Reply out = ok_reply();
  out["rooms"] = Reply::array();
  for (const auto id : host.room_ids()) out["rooms"].push_back(room_json(host, *host.room(id)));
  return out;
}

Reply players(GameHost& host, const nlohmann::json& req, std::uint64_t) {
  std::optional<std::uint32_t> only;
  if (req.contains("room")) {
    const Room* r = find_room(host, req["room"]);
    if (!r) return error_reply("no such room: " + req["room"].dump());
    only = r->id();
  }
  Reply out = ok_reply();
  out["players"] = Reply::array();
  for (const auto& s : host.endpoint().sessions()) {
    if (only && s.room != *only) continue;
    Reply p;
    p["player"] = s.player_id;
    const Room* r = host.room(s.room);
    p["name"] = r ? r->shown_name(s.player_id, s.name) : s.name;  // as the players' screens show it
    p["room"] = r ? r->code() : "";
    p["spectator"] = s.spectator;
    p["connected"] = s.connected;
    p["address"] = s.address;
    p["rtt_ms"] = s.rtt_ms;
    out["players"].push_back(p);
  }
  return out;
}

Reply kick(GameHost& host, const nlohmann::json& req, std::uint64_t now_ms) {
  const auto id = u32_of(req, "player");
  if (!id) return error_reply("kick needs \"player\": a player id (see players)");
  const auto sessions = host.endpoint().sessions();
  if (std::none_of(sessions.begin(), sessions.end(), [&](const auto& s) { return s.player_id == *id; }))
    return error_reply("no player " + std::to_string(*id));
  const std::string reason = req.contains("reason") && req["reason"].is_string() ? req["reason"].get<std::string>() : "";
  host.kick(*id, protocol::ErrorCode::kicked, reason.empty() ? "kicked by the host" : "kicked by the host: " + reason, now_ms);
  Reply out = ok_reply();
  out["kicked"] = *id;
  return out;
}

Reply ban(GameHost& host, const nlohmann::json& req, std::uint64_t now_ms) {
  if (!req.contains("address") || !req["address"].is_string())
    return error_reply("ban needs \"address\": an IP address (the port is ignored)");
  const std::string address(protocol::host_of(req["address"].get<std::string>()));
  std::uint64_t minutes = 60;
  if (req.contains("minutes")) {
    if (!req["minutes"].is_number_unsigned() || req["minutes"].get<std::uint64_t>() < 1 ||
        req["minutes"].get<std::uint64_t>() > 525600)
      return error_reply("minutes must be 1..525600");
    minutes = req["minutes"].get<std::uint64_t>();
  }
  if (address.empty()) return error_reply("ban needs an IP address");
  host.bans().ban(address, now_ms + minutes * 60000);
  std::vector<std::uint32_t> kicked;
  for (const auto& s : host.endpoint().sessions())
    if (protocol::host_of(s.address) == address) kicked.push_back(s.player_id);
  for (auto id : kicked)
    host.kick(id, protocol::ErrorCode::banned, "banned by the host for " + std::to_string(minutes) + " minutes", now_ms);
  Reply out = ok_reply();
  out["banned"] = address;
  out["minutes"] = minutes;
  out["kicked"] = kicked;
  return out;
}

Reply announce(GameHost& host, const nlohmann::json& req, std::uint64_t now_ms) {
  if (!req.contains("text") || !req["text"].is_string() ||
      ChatRelay::clean(req["text"].get<std::string>(), protocol::kMaxTextBytes).empty())
    return error_reply("announce needs \"text\": a line with something printable");
  Reply out = ok_reply();
  out["told"] = host.announce(req["text"].get<std::string>(), now_ms);
  return out;
}

Reply close(GameHost& host, const nlohmann::json& req, std::uint64_t now_ms) {
  const Room* r = req.contains("room") ? find_room(host, req["room"]) : nullptr;
  if (!r) return error_reply("close needs \"room\": the code or id of an open room");
  Reply out = ok_reply();
  out["closed"] = r->code();
  host.close_room(r->id(), protocol::ErrorCode::room_closed, "the host closed this room", now_ms);
  return out;
}

Reply drain(GameHost& host, const nlohmann::json&, std::uint64_t) {
  host.stop_new_rooms();
  Reply out = ok_reply();
  out["draining"] = true;
  out["rooms"] = host.room_ids().size();
  return out;
}

Reply stats(GameHost& host, const nlohmann::json&, std::uint64_t) {
  std::size_t players = 0, spectators = 0;
  for (const auto& s : host.endpoint().sessions()) (s.spectator ? spectators : players) += s.connected ? 1 : 0;
  Reply out = ok_reply();
  out["rooms"] = host.room_ids().size();
  out["handovers"] = {{"moved", host.rooms_moved()}, {"adopted", host.rooms_adopted()},
                      {"refused", host.handovers_refused()}, {"forgotten", host.rooms_forgotten()}};
  out["max_rooms"] = host.options().max_rooms;
  out["rooms_made"] = host.rooms_made();
  out["players"] = players;
  out["spectators"] = spectators;
  out["sessions"] = host.endpoint().sessions().size();
  out["draining"] = host.draining();
  out["bans"] = host.bans().size();
  out["banned_datagrams"] = host.bans().dropped_datagrams();
  out["rejected_datagrams"] = host.endpoint().rejects().total();
  out["skipped_ticks"] = host.stats().skipped_ticks;
  const auto journal = host.journal_health();
  out["journal"] = {{"rooms", journal.rooms}, {"failing", journal.failing}, {"failures", journal.failures},
                    {"error", journal.error}};
  if (const auto* w = host.profiles()) {
    const auto ps = w->stats();
    out["profiles"] = {{"where", ps.where}, {"connected", ps.connected}, {"error", ps.error}, {"queued", ps.queued},
                       {"spooled", ps.pending}, {"results", ps.results}, {"duplicates", ps.duplicates},
                       {"dropped", ps.dropped}, {"failures", ps.failures}, {"adopted", ps.adopted}};
  } else {
    out["profiles"] = "off";
  }
  return out;
}

Reply help(GameHost&, const nlohmann::json&, std::uint64_t) {
  Reply out = ok_reply();
  out["commands"] = Reply::array();
  for (const ConsoleCommand& c : console_commands())
    out["commands"].push_back({{"name", c.name}, {"usage", c.usage}, {"does", c.does}});
  return out;
}

// ---- the front end's words ------------------------------------------------------------

std::string joined(Words words) {
  std::string s;
  for (std::size_t i = 0; i < words.size(); ++i) s += (i ? " " : "") + words[i];
  return s;
}

// A decimal number of at most 12 digits.
std::optional<std::uint64_t> number_word(const std::string& s) {
  if (s.empty() || s.size() > 12 || s.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoull(s);
}

std::string no_words(Words, nlohmann::json&) { return ""; }

// With --profiles on, the server answers these off the tick (net/udp_server.cpp, the
// profile writer's thread); here only when they are off.
Reply profiles_off(GameHost&, const nlohmann::json&, std::uint64_t) {
  return error_reply("profiles are off (fts-server --profiles off)");
}

std::string top_words(Words w, nlohmann::json& req) {
  for (const auto& word : w) {
    if (word == "level" || word == "knocks") req["board"] = word;
    else if (const auto n = number_word(word)) req["n"] = *n;
    else return "top [level|knocks] [N]";
  }
  return "";
}

std::string profile_words(Words w, nlohmann::json& req) {
  if (w.size() != 1) return "profile NAME|FINGERPRINT";
  req["who"] = w[0];
  return "";
}

std::string room_word(Words w, nlohmann::json& req) {
  if (!w.empty()) req["room"] = w[0];
  return "";
}

std::string room_required(Words w, nlohmann::json& req) { return w.empty() ? "close ROOM" : room_word(w, req); }

std::string kick_words(Words w, nlohmann::json& req) {
  if (w.empty()) return "kick PLAYER [REASON]";
  const auto id = number_word(w[0]);
  if (!id) return "PLAYER must be a number, got \"" + w[0] + "\"";
  req["player"] = *id;
  if (const std::string reason = joined(w.subspan(1)); !reason.empty()) req["reason"] = reason;
  return "";
}

std::string ban_words(Words w, nlohmann::json& req) {
  if (w.empty()) return "ban ADDRESS [MINUTES]";
  req["address"] = w[0];
  if (w.size() > 1) {
    const auto minutes = number_word(w[1]);
    if (!minutes) return "MINUTES must be a number, got \"" + w[1] + "\"";
    req["minutes"] = *minutes;
  }
  return "";
}

// The words are the line, as `kick`'s reason: quoting is optional.
std::string announce_words(Words w, nlohmann::json& req) {
  const std::string text = joined(w);
  if (text.find_first_not_of(' ') == std::string::npos) return "announce TEXT: the line every player is shown";
  req["text"] = text;
  return "";
}

// `handover` is answered by the loop once the peer has (net/handover.hpp); here only
// when the server has no fleet secret.
Reply handover_off(GameHost&, const nlohmann::json&, std::uint64_t) {
  return error_reply("this server hands no rooms over: it needs --fleet-secret FILE and --journal-dir DIR");
}

std::string handover_words(Words w, nlohmann::json& req) {
  if (w.size() != 2) return "handover ROOM|all PEER";
  req["room"] = w[0];
  req["peer"] = w[1];
  return "";
}

constexpr ConsoleCommand kCommands[] = {
    {"rooms", "rooms", "every room: id, code, privacy, players, spectators, level, phase, tick, seed, state hash",
     rooms, no_words},
    {"players", "players [ROOM]", "the sessions (of one room): id, name, room, spectator, connected, address, RTT",
     players, room_word},
    {"kick", "kick PLAYER [REASON]", "ends the player's session; its client is told why", kick, kick_words},
    {"ban", "ban ADDRESS [MINUTES]", "kicks the address's sessions and drops its datagrams for MINUTES (60)", ban,
     ban_words},
    {"announce", "announce TEXT", "a chat line from the host to every connected client", announce, announce_words},
    {"close", "close ROOM", "closes the room (its clients are told room_closed)", close, room_required},
    {"drain", "drain", "no new rooms; the server exits 0 when the last room has closed", drain, no_words},
    {"handover", "handover ROOM|all PEER",
     "hands the room (all: drains, and every room) to the server at PEER (its --handover-listen); its clients follow",
     handover_off, handover_words},
    {"stats", "stats", "rooms, players, spectators, sessions, bans, dropped datagrams, skipped ticks, the journal (failing rooms)", stats, no_words},
    {"top", "top [level|knocks] [N]",
     "the leaderboard (profiles): best level (ties by coins) or most knocks, the first N (10)", profiles_off,
     top_words},
    {"profile", "profile NAME|FINGERPRINT", "a player's profile and ranks (profiles)", profiles_off, profile_words},
    {"help", "help", "these commands", help, no_words},
};

const ConsoleCommand* find_command(std::string_view name) {
  for (const ConsoleCommand& c : kCommands)
    if (c.name == name) return &c;
  return nullptr;
}

std::string command_list(std::string_view ConsoleCommand::*what) {
  std::string s;
  for (const ConsoleCommand& c : kCommands) s += (s.empty() ? "" : ", ") + std::string(c.*what);
  return s;
}

}  // namespace

std::span<const ConsoleCommand> console_commands() { return kCommands; }

Reply console_command(GameHost& host, const nlohmann::json& req, std::uint64_t now_ms) {
  const Reply reply = [&] {
    if (!req.is_object() || !req.contains("cmd") || !req["cmd"].is_string())
      return error_reply("a request is a JSON object with a \"cmd\" string");
    const std::string name = req["cmd"].get<std::string>();
    const ConsoleCommand* c = find_command(name);
    if (!c) return error_reply("unknown command \"" + name + "\"; commands: " + command_list(&ConsoleCommand::name));
    return c->handler(host, req, now_ms);
  }();
  const std::string request_text = req.dump();
  if (reply.value("ok", false)) {
    log_record(spdlog::level::info, "console", {{"request", std::string_view(request_text)}, {"ok", true}});
  } else {
    log_record(spdlog::level::warn, "console",
               {{"request", std::string_view(request_text)}, {"ok", false},
                {"error", std::string_view(reply["error"].get_ref<const std::string&>())}});
  }
  return reply;
}

// A request nests at most kConsoleMaxDepth deep (they are flat objects): the log's copy
// of it is written by dump(), which recurses once per level, and a line of 32000 '['
// overflowed the stack. The strict parser's walk does not recurse.
Reply console_line(GameHost& host, const std::string& line, std::uint64_t now_ms) {
  std::string why;
  const auto request = room::parse_json(line, why, kConsoleMaxDepth);
  if (request) return console_command(host, *request, now_ms);
  // The parser's message quotes the bytes it stopped at, which need not be UTF-8 (found by
  // fts_fuzz_console): the reply is JSON, so they are shown as '?'.
  for (char& c : why)
    if (static_cast<unsigned char>(c) < 0x20 || static_cast<unsigned char>(c) > 0x7e) c = '?';
  const Reply reply = error_reply("not a JSON request: " + why);
  log_record(spdlog::level::warn, "console",
             {{"request", "(refused unread)"}, {"ok", false},
              {"error", std::string_view(reply["error"].get_ref<const std::string&>())}});
  return reply;
}

std::string console_request(const std::vector<std::string>& words, std::string& error) {
  if (words.empty()) {
    error = "a command is needed: " + command_list(&ConsoleCommand::usage);
    return "";
  }
  const std::string& name = words[0];
  if (!name.empty() && name.front() == '{') return name;  // a request object as is
  nlohmann::json j;
  j["cmd"] = name;
  if (const ConsoleCommand* c = find_command(name)) {
    error = c->from_words(Words(words).subspan(1), j);
    if (!error.empty()) return "";
  }
  try {
    return j.dump();
  } catch (const nlohmann::json::type_error&) {  // found by fts_fuzz_console
    error = "the command and its words must be UTF-8 text";
    return "";
  }
}

}  // namespace fts::server
