// GameHost's console (the host's local socket, JSON lines; README "Hosting"): one request
// in, one reply out. The socket itself is server/net/console.cpp's.
#include "app/game_host.hpp"
#include "app/room_codes.hpp"
#include "fts/room/text.hpp"

namespace fts::server {
namespace {

nlohmann::ordered_json error_reply(const std::string& message) {
  nlohmann::ordered_json j;
  j["ok"] = false;
  j["error"] = message;
  return j;
}

}  // namespace

nlohmann::ordered_json GameHost::room_json(const Room& r) const {
  nlohmann::ordered_json j;
  j["id"] = r.id();
  j["code"] = r.code();
  j["private"] = r.is_private();
  j["players"] = endpoint_.seats_in_room(r.id());
  j["spectators"] = endpoint_.spectators_in_room(r.id());
  j["level"] = r.match().level;
  j["phase"] = std::string(sim::to_string(r.match().phase));
  j["tick"] = r.match().tick;
  j["seed"] = r.seed();
  j["state_hash"] = room::hex16(sim::match_hash(r.match()));
  return j;
}

// One console request: {"cmd":"rooms"}, {"cmd":"players","room":"ABCDE"}, {"cmd":"kick",
// "player":3,"reason":"..."}, {"cmd":"ban","address":"10.0.0.7","minutes":60},
// {"cmd":"announce","text":"..."}, {"cmd":"close","room":"ABCDE"}, {"cmd":"drain"}, {"cmd":"stats"}.
nlohmann::ordered_json GameHost::command(const nlohmann::json& req, std::uint64_t now_ms) {
  auto reply = [&]() -> nlohmann::ordered_json {
    if (!req.is_object() || !req.contains("cmd") || !req["cmd"].is_string())
      return error_reply("a request is a JSON object with a \"cmd\" string");
    const std::string cmd = req["cmd"].get<std::string>();
    // A room by code ("ABCDE", any case) or id (3).
    auto find_room = [&](const nlohmann::json& v) -> const Room* {
      if (v.is_number_unsigned())
        return v.get<std::uint64_t>() > 0xFFFFFFFFull ? nullptr : room(static_cast<std::uint32_t>(v.get<std::uint64_t>()));
      if (v.is_string())
        if (auto code = normalize_room_code(v.get<std::string>())) return room_by_code(*code);
      return nullptr;
    };
    nlohmann::ordered_json out;
    out["ok"] = true;
    if (cmd == "rooms") {
      out["rooms"] = nlohmann::ordered_json::array();
      for (const auto& [id, r] : rooms_) out["rooms"].push_back(room_json(*r));
    } else if (cmd == "players") {
      std::optional<std::uint32_t> only;
      if (req.contains("room")) {
        const Room* r = find_room(req["room"]);
        if (!r) return error_reply("no such room: " + req["room"].dump());
        only = r->id();
      }
      out["players"] = nlohmann::ordered_json::array();
      for (const auto& s : endpoint_.sessions()) {
        if (only && s.room != *only) continue;
        nlohmann::ordered_json p;
        p["player"] = s.player_id;
        const Room* r = room(s.room);
        p["name"] = r ? r->shown_name(s.player_id, s.name) : s.name;  // as the players' screens show it
        p["room"] = r ? r->code() : "";
        p["spectator"] = s.spectator;
        p["connected"] = s.connected;
        p["address"] = s.address;
        p["rtt_ms"] = s.rtt_ms;
        out["players"].push_back(p);
      }
    } else if (cmd == "kick") {
      if (!req.contains("player") || !req["player"].is_number_unsigned() ||
          req["player"].get<std::uint64_t>() > 0xFFFFFFFFull)
        return error_reply("kick needs \"player\": a player id (see players)");
      const auto id = static_cast<std::uint32_t>(req["player"].get<std::uint64_t>());
      const auto sessions = endpoint_.sessions();
      if (std::none_of(sessions.begin(), sessions.end(), [&](const auto& s) { return s.player_id == id; }))
        return error_reply("no player " + std::to_string(id));
      std::string reason = req.contains("reason") && req["reason"].is_string() ? req["reason"].get<std::string>() : "";
      endpoint_.kick(id, "kicked", reason.empty() ? "kicked by the host" : "kicked by the host: " + reason, now_ms);
      out["kicked"] = id;
    } else if (cmd == "ban") {
      if (!req.contains("address") || !req["address"].is_string())
        return error_reply("ban needs \"address\": an IP address (the port is ignored)");
      const std::string host(protocol::host_of(req["address"].get<std::string>()));
      std::uint64_t minutes = 60;
      if (req.contains("minutes")) {
        if (!req["minutes"].is_number_unsigned() || req["minutes"].get<std::uint64_t>() < 1 ||
            req["minutes"].get<std::uint64_t>() > 525600)
          return error_reply("minutes must be 1..525600");
        minutes = req["minutes"].get<std::uint64_t>();
      }
      if (host.empty()) return error_reply("ban needs an IP address");
      bans_[host] = now_ms + minutes * 60000;
      std::vector<std::uint32_t> kicked;
      for (const auto& s : endpoint_.sessions())
        if (protocol::host_of(s.address) == host) kicked.push_back(s.player_id);
      for (auto id : kicked)
        endpoint_.kick(id, "banned", "banned by the host for " + std::to_string(minutes) + " minutes", now_ms);
      out["banned"] = host;
      out["minutes"] = minutes;
      out["kicked"] = kicked;
    } else if (cmd == "close") {
      const Room* r = req.contains("room") ? find_room(req["room"]) : nullptr;
      if (!r) return error_reply("close needs \"room\": the code or id of an open room");
      out["closed"] = r->code();
      close_room(r->id(), "room_closed", "the host closed this room", now_ms);
    } else if (cmd == "announce") {
      if (!req.contains("text") || !req["text"].is_string() || ChatRelay::clean(req["text"].get<std::string>(), protocol::kMaxTextBytes).empty())
        return error_reply("announce needs \"text\": a line with something printable");
      out["told"] = announce(req["text"].get<std::string>(), now_ms);
    } else if (cmd == "drain") {
      draining_ = true;
      out["draining"] = true;
      out["rooms"] = rooms_.size();
      if (rooms_.empty()) log_record(spdlog::level::info, "drained", {});
    } else if (cmd == "stats") {
      std::size_t players = 0, spectators = 0;
      for (const auto& s : endpoint_.sessions()) (s.spectator ? spectators : players) += s.connected ? 1 : 0;
      out["rooms"] = rooms_.size();
      out["max_rooms"] = options_.max_rooms;
      out["rooms_made"] = rooms_made_;
      out["players"] = players;
      out["spectators"] = spectators;
      out["sessions"] = endpoint_.sessions().size();
      out["draining"] = draining_;
      out["bans"] = bans_.size();
      out["banned_datagrams"] = banned_datagrams_;
      out["rejected_datagrams"] = endpoint_.rejects().total();
      out["skipped_ticks"] = stats_.skipped_ticks;
    } else {
      return error_reply("unknown command \"" + cmd + "\"; commands: rooms, players, kick, ban, announce, close, drain, stats");
    }
    return out;
  }();
  const std::string request_text = req.dump();
  const bool ok = reply.value("ok", false);
  if (ok) log_record(spdlog::level::info, "console", {{"request", std::string_view(request_text)}, {"ok", ok}});
  else
    log_record(spdlog::level::warn, "console",
               {{"request", std::string_view(request_text)}, {"ok", ok},
                {"error", std::string_view(reply["error"].get_ref<const std::string&>())}});
  return reply;
}

}  // namespace fts::server
