#include "app/profile_setup.hpp"

#include <filesystem>

namespace fts::server {
namespace {

nlohmann::ordered_json profile_json(const profiles::Profile& p) {
  return {{"fingerprint", p.fingerprint}, {"name", p.name},           {"first_seen", p.first_seen},
          {"last_seen", p.last_seen},     {"matches", p.matches},     {"best_level", p.best_level},
          {"best_level_coins", p.best_level_coins}, {"most_coins", p.most_coins}, {"knocks", p.knocks},
          {"lives_lost", p.lives_lost},   {"play_s", p.play_ms / 1000}};
}

bool is_fingerprint(const std::string& s) {
  if (s.size() != 32) return false;
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

}  // namespace

ProfilePlace profile_place(const std::string& value, const char* xdg_state_home, const char* home) {
  ProfilePlace p;
  if (value == "off") {
    p.off = true;
    return p;
  }
  std::string state;
  if (xdg_state_home && *xdg_state_home == '/') state = xdg_state_home;
  else if (home && *home) state = std::string(home) + "/.local/state";
  const std::string server_dir = state.empty() ? std::string() : state + "/fear-the-sphere/server";
  if (value.empty()) {
    if (server_dir.empty()) {
      p.error = "--profiles: no state directory for the default SQLite file (set HOME or XDG_STATE_HOME, give "
                "--profiles FILE, or --profiles off)";
      return p;
    }
    p.url = server_dir + "/profiles.sqlite";
  } else {
    p.url = value;
  }
  if (profiles::is_postgresql_url(p.url)) {
    // A fleet's servers each spool locally until the shared database takes the writes.
    if (server_dir.empty()) {
      p.error = "--profiles: no state directory for the spool (set HOME or XDG_STATE_HOME)";
      return p;
    }
    p.spool_dir = server_dir + "/profile-spool";
  } else {
    std::string path = p.url.rfind("sqlite:", 0) == 0 ? p.url.substr(p.url.find(':') + 1) : p.url;
    std::filesystem::path f(path);
    std::error_code ec;
    if (!f.parent_path().empty()) std::filesystem::create_directories(f.parent_path(), ec);
    p.spool_dir = path + ".spool";
  }
  return p;
}

nlohmann::ordered_json profiles_reply(profiles::Store* store, const nlohmann::json& request) {
  const std::string cmd = request.value("cmd", "");
  if (!store) return {{"ok", false}, {"error", "the profile database is not reachable now (see stats, /metrics)"}};
  try {
    if (cmd == "top") {
      const std::string board = request.value("board", "level");
      if (board != "level" && board != "knocks") return {{"ok", false}, {"error", "top: the board is level or knocks"}};
      const auto n = std::clamp<std::int64_t>(request.value("n", std::int64_t{10}), 1, 100);
      const auto b = board == "level" ? profiles::Board::level : profiles::Board::knocks;
      nlohmann::ordered_json rows = nlohmann::ordered_json::array();
      std::int64_t rank = 0;
      for (const auto& p : store->top(b, static_cast<std::size_t>(n))) {
        auto row = profile_json(p);
        row["rank"] = ++rank;
        rows.push_back(std::move(row));
      }
      return {{"ok", true}, {"board", board}, {"where", store->where()}, {"profiles", store->profiles()}, {"top", rows}};
    }
    if (cmd == "profile") {
      const std::string who = request.value("who", "");
      std::vector<profiles::Profile> found;
      if (is_fingerprint(who)) {
        if (auto p = store->profile(who)) found.push_back(*p);
      } else {
        found = store->by_name(who, 10);
      }
      if (found.empty()) return {{"ok", false}, {"error", "no profile named or keyed " + who}};
      nlohmann::ordered_json rows = nlohmann::ordered_json::array();
      for (const auto& p : found) {
        auto row = profile_json(p);
        row["rank_level"] = store->rank(profiles::Board::level, p.fingerprint);
        row["rank_knocks"] = store->rank(profiles::Board::knocks, p.fingerprint);
        rows.push_back(std::move(row));
      }
      return {{"ok", true}, {"profiles", rows}};
    }
  } catch (const std::exception& e) {
    return {{"ok", false}, {"error", std::string("the profile database failed: ") + e.what()}};
  }
  return {{"ok", false}, {"error", "not a profile command"}};
}

}  // namespace fts::server
