#include "net/identity_store.hpp"
#include "net/session_store.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace fts::client {
namespace {

std::string errno_text() { return std::strerror(errno); }

}  // namespace

std::string default_identity_path(const std::string& state_dir) {
  return state_dir.empty() ? std::string() : state_dir + "/fear-the-sphere/identity";
}

std::optional<protocol::Identity> load_or_create_identity(const std::string& path, std::string& why) {
  if (path.empty()) {
    why = "no identity file (set HOME or XDG_STATE_HOME, or give --identity FILE)";
    return std::nullopt;
  }
  int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOFOLLOW);
  if (fd >= 0) {
    struct stat st {};
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
      ::close(fd);
      why = path + " is not a regular file";
      return std::nullopt;
    }
    if ((st.st_mode & 077) != 0) {
      ::close(fd);
      why = path + " may be read by others (mode " + std::to_string((st.st_mode >> 6) & 7) +
            std::to_string((st.st_mode >> 3) & 7) + std::to_string(st.st_mode & 7) + "): chmod 600 it";
      return std::nullopt;
    }
    char buf[256];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    ::close(fd);
    auto id = n > 0 ? protocol::parse_identity_file(std::string_view(buf, static_cast<std::size_t>(n))) : std::nullopt;
    if (!id) why = path + " is not a Fear The Sphere identity (one line: fts-identity-1 and 64 hex digits)";
    return id;
  }
  if (errno != ENOENT) {
    why = "cannot read " + path + ": " + errno_text();
    return std::nullopt;
  }
  // The first run: a new key, written to a file made 0600 from the start.
  const auto slash = path.rfind('/');
  if (slash != std::string::npos && slash > 0 && !make_private_dirs(path.substr(0, slash))) {
    why = "cannot create " + path.substr(0, slash) + ": " + errno_text();
    return std::nullopt;
  }
  const protocol::Identity id = protocol::new_identity();
  const std::string tmp = path + ".tmp." + std::to_string(::getpid());
  fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC | O_NOFOLLOW, 0600);
  if (fd < 0) {
    why = "cannot write " + tmp + ": " + errno_text();
    return std::nullopt;
  }
  const std::string text = protocol::identity_file_text(id);
  const bool ok = ::write(fd, text.data(), text.size()) == static_cast<ssize_t>(text.size()) && ::fsync(fd) == 0;
  ::close(fd);
  // link(2), not rename: two clients making one at once keep the first (the other reads it).
  const int linked = ok ? ::link(tmp.c_str(), path.c_str()) : -1;
  const bool raced = linked != 0 && ok && errno == EEXIST;
  if (!ok || (linked != 0 && !raced)) why = "cannot write " + path + ": " + errno_text();
  ::unlink(tmp.c_str());
  if (raced) return load_or_create_identity(path, why);
  if (linked != 0) return std::nullopt;
  return id;
}

}  // namespace fts::client
