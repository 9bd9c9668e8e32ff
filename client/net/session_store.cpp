#include "net/session_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cctype>
#include <cstring>
#include <fstream>

namespace fts::client {
namespace {

bool is_token(const std::string& s) {
  if (s.size() != 32) return false;
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'))) return false;
  return true;
}

// "host:port" as a file name: letters, digits, '.', '-' kept; anything else becomes '_'.
std::string file_name(const std::string& server) {
  std::string out;
  for (char c : server)
    out += (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') ? c : '_';
  return out.empty() ? "server" : out;
}

}  // namespace

bool make_private_dirs(const std::string& path) {
  for (std::size_t i = 1; i <= path.size(); ++i) {
    if (i != path.size() && path[i] != '/') continue;
    const std::string part = path.substr(0, i);
    if (::mkdir(part.c_str(), 0700) != 0 && errno != EEXIST) return false;
  }
  return true;
}

std::string state_dir(const char* xdg_state_home, const char* home) {
  if (xdg_state_home && *xdg_state_home == '/') return xdg_state_home;  // the spec: absolute only
  if (home && *home) return std::string(home) + "/.local/state";
  return "";
}

SessionStore::SessionStore(std::string dir, const std::string& server) : dir_(std::move(dir)) {
  if (!dir_.empty()) {
    dir_ += "/fear-the-sphere/sessions";
    path_ = dir_ + "/" + file_name(server);
  }
}

std::optional<std::string> SessionStore::load() const {
  if (path_.empty()) return std::nullopt;
  std::ifstream in(path_);
  std::string token;
  if (!(in >> token) || !is_token(token)) return std::nullopt;
  return token;
}

bool SessionStore::save(const std::string& token, std::string& why) const {
  if (path_.empty()) {
    why = "no state directory (set HOME or XDG_STATE_HOME)";
    return false;
  }
  if (!make_private_dirs(dir_)) {
    why = "cannot create " + dir_ + ": " + std::strerror(errno);
    return false;
  }
  // Written to a temporary file made 0600 from the start, then renamed over the old one.
  const std::string tmp = path_ + ".tmp";
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0600);
  if (fd < 0) {
    why = "cannot write " + tmp + ": " + std::strerror(errno);
    return false;
  }
  const std::string line = token + "\n";
  const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
  ::close(fd);
  if (!ok || ::rename(tmp.c_str(), path_.c_str()) != 0) {
    why = "cannot write " + path_ + ": " + std::strerror(errno);
    ::unlink(tmp.c_str());
    return false;
  }
  return true;
}

void SessionStore::forget() const {
  if (!path_.empty()) ::unlink(path_.c_str());
}

}  // namespace fts::client
