// Where fts-client keeps its session token per server, so that a restarted client takes
// its player back (within the server's reconnect window): one file per server under
// $XDG_STATE_HOME/fear-the-sphere/sessions/ (default ~/.local/state), readable by the
// user alone (0600 in a 0700 directory).
#pragma once

#include <optional>
#include <string>

namespace fts::client {

// The state directory from XDG_STATE_HOME / HOME (both as given; "" if neither is set).
std::string state_dir(const char* xdg_state_home, const char* home);

// Makes every missing directory of `path` with mode 0700 (the state is private); false,
// with errno set, when one cannot be made.
bool make_private_dirs(const std::string& path);

class SessionStore {
 public:
  // dir: the state directory ("" keeps nothing); server: "host:port" as typed.
  SessionStore(std::string dir, const std::string& server);

  // The saved token, if there is one that looks like a token (32 hex digits).
  std::optional<std::string> load() const;
  // Saves (or replaces) the token; returns false with `why` set if it cannot.
  bool save(const std::string& token, std::string& why) const;
  // Forgets the token (a refused or expired one).
  void forget() const;
  const std::string& path() const { return path_; }

 private:
  std::string dir_;
  std::string path_;
};

}  // namespace fts::client
