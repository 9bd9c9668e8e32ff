#include "net/console.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

namespace fts::server {

namespace asio = boost::asio;
using local = asio::local::stream_protocol;

struct ConsoleServer::Connection : std::enable_shared_from_this<ConsoleServer::Connection> {
  Connection(local::socket s, std::function<std::string(const std::string&)>& h, std::shared_ptr<std::size_t> open)
      : socket(std::move(s)), buffer(kMaxLineBytes), handle(h), open_count(std::move(open)) {
    ++*open_count;
  }
  ~Connection() { --*open_count; }

  void read() {
    auto self = shared_from_this();
    asio::async_read_until(socket, buffer, '\n', [self](const boost::system::error_code& ec, std::size_t n) {
      if (ec) return;  // closed, or a line over kMaxLineBytes: the connection ends
      std::string line(asio::buffers_begin(self->buffer.data()), asio::buffers_begin(self->buffer.data()) + n);
      self->buffer.consume(n);
      while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
      if (line.empty()) return self->read();
      self->reply = self->handle(line) + "\n";
      asio::async_write(self->socket, asio::buffer(self->reply), [self](const boost::system::error_code& e, std::size_t) {
        if (!e) self->read();
      });
    });
  }

  local::socket socket;
  asio::streambuf buffer;
  std::string reply;
  std::function<std::string(const std::string&)>& handle;
  std::shared_ptr<std::size_t> open_count;
};

ConsoleServer::ConsoleServer(asio::io_context& io, std::string path, std::function<std::string(const std::string&)> handle)
    : io_(io), path_(std::move(path)), handle_(std::move(handle)), acceptor_(io) {}

ConsoleServer::~ConsoleServer() {
  boost::system::error_code ec;
  acceptor_.close(ec);
  if (bound_) ::unlink(path_.c_str());
}

std::string ConsoleServer::start() {
  std::error_code fec;
  const auto st = std::filesystem::symlink_status(path_, fec);
  if (!fec && std::filesystem::exists(st)) {
    if (st.type() != std::filesystem::file_type::socket)
      return "--console-socket: " + path_ + " exists and is not a socket; not replacing it";
    ::unlink(path_.c_str());  // a stale socket of an earlier run
  }
  boost::system::error_code ec;
  acceptor_.open(local(), ec);
  if (ec) return "--console-socket: " + ec.message();
  // Created owner-only: the umask covers the moment between bind and chmod.
  const mode_t old = ::umask(0177);
  acceptor_.bind(local::endpoint(path_), ec);
  ::umask(old);
  if (ec) return "--console-socket: cannot bind " + path_ + ": " + ec.message();
  bound_ = true;
  if (::chmod(path_.c_str(), 0600) != 0) return "--console-socket: chmod " + path_ + ": " + std::strerror(errno);
  acceptor_.listen(4, ec);
  if (ec) return "--console-socket: listen: " + ec.message();
  accept();
  return "";
}

void ConsoleServer::accept() {
  acceptor_.async_accept([this](const boost::system::error_code& ec, local::socket s) {
    if (ec == asio::error::operation_aborted) return;
    if (!ec && *open_ < kMaxConnections) std::make_shared<Connection>(std::move(s), handle_, open_)->read();
    accept();
  });
}

std::string console_request(const std::vector<std::string>& words, std::string& error) {
  if (words.empty()) {
    error = "a command is needed: rooms, players [ROOM], kick PLAYER [REASON], ban ADDRESS [MINUTES], announce TEXT, "
            "close ROOM, drain, stats";
    return "";
  }
  const std::string& cmd = words[0];
  if (!cmd.empty() && cmd.front() == '{') return cmd;  // a request object as is
  nlohmann::json j;
  j["cmd"] = cmd;
  auto number = [&](const std::string& s, const char* what) -> std::optional<std::uint64_t> {
    std::uint64_t v = 0;
    if (s.empty() || s.size() > 12 || s.find_first_not_of("0123456789") != std::string::npos) {
      error = std::string(what) + " must be a number, got \"" + s + "\"";
      return std::nullopt;
    }
    v = std::stoull(s);
    return v;
  };
  if (cmd == "players" && words.size() > 1) {
    j["room"] = words[1];
  } else if (cmd == "kick") {
    if (words.size() < 2) return error = "kick PLAYER [REASON]", "";
    auto id = number(words[1], "PLAYER");
    if (!id) return "";
    j["player"] = *id;
    std::string reason;
    for (std::size_t i = 2; i < words.size(); ++i) reason += (i > 2 ? " " : "") + words[i];
    if (!reason.empty()) j["reason"] = reason;
  } else if (cmd == "ban") {
    if (words.size() < 2) return error = "ban ADDRESS [MINUTES]", "";
    j["address"] = words[1];
    if (words.size() > 2) {
      auto m = number(words[2], "MINUTES");
      if (!m) return "";
      j["minutes"] = *m;
    }
  } else if (cmd == "announce") {
    // The words after the command are the line, as `kick`'s reason: quoting is optional.
    std::string text;
    for (std::size_t i = 1; i < words.size(); ++i) text += (i > 1 ? " " : "") + words[i];
    if (text.find_first_not_of(' ') == std::string::npos) return error = "announce TEXT: the line every player is shown", "";
    j["text"] = text;
  } else if (cmd == "close") {
    if (words.size() < 2) return error = "close ROOM", "";
    j["room"] = words[1];
  }
  return j.dump();
}

int run_console_client(const std::string& path, const std::vector<std::string>& words) {
  std::string error;
  const std::string request = console_request(words, error);
  if (request.empty()) {
    std::cerr << "fts-server --console: " << error << "\n";
    return 2;
  }
  asio::io_context io;
  local::socket s(io);
  boost::system::error_code ec;
  s.connect(local::endpoint(path), ec);
  if (ec) {
    std::cerr << "fts-server --console: cannot connect to " << path << ": " << ec.message()
              << " (is the server running with --console-socket " << path << "?)\n";
    return 2;
  }
  asio::write(s, asio::buffer(request + "\n"), ec);
  asio::streambuf buffer;
  const std::size_t n = ec ? 0 : asio::read_until(s, buffer, '\n', ec);
  if (ec || n == 0) {
    std::cerr << "fts-server --console: no answer from " << path << "\n";
    return 2;
  }
  const std::string line(asio::buffers_begin(buffer.data()), asio::buffers_begin(buffer.data()) + n);
  std::cout << line;
  const auto reply = nlohmann::json::parse(line, nullptr, false);
  return reply.is_object() && reply.value("ok", false) ? 0 : 1;
}

}  // namespace fts::server
