// Where fts-server keeps players' profiles (--profiles, issue 41), and what the console's
// `top` and `profile` answer from the store.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "profiles/store.hpp"
#include "profiles/writer.hpp"

namespace fts::server {

struct ProfilePlace {
  bool off = false;
  std::string url;         // Store::open's
  std::string spool_dir;   // the writer's spool
  std::string error;       // why none can be had (no state directory)
};

// --profiles VALUE with the environment's XDG_STATE_HOME and HOME (as given, may be null).
ProfilePlace profile_place(const std::string& value, const char* xdg_state_home, const char* home);

// The console's `top [level|knocks] [N]` and `profile NAME|FINGERPRINT` against a store
// (nullptr: the database is not reachable now).
nlohmann::ordered_json profiles_reply(profiles::Store* store, const nlohmann::json& request);

}  // namespace fts::server
