#include "net/console.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <iostream>

#include <nlohmann/json.hpp>

#include "app/console_commands.hpp"
#include "app/log.hpp"

namespace fts::server {

namespace asio = boost::asio;
using local = asio::local::stream_protocol;

struct ConsoleServer::Connection : std::enable_shared_from_this<ConsoleServer::Connection> {
  using Deferred = ConsoleServer::Deferred;
  Connection(local::socket s, std::function<std::string(const std::string&)>& h, Deferred& d,
             std::shared_ptr<std::size_t> open, std::shared_ptr<std::size_t> unanswered, std::shared_ptr<Counters> c)
      : socket(std::move(s)), timer(socket.get_executor()), buffer(kMaxLineBytes), handle(h), deferred(d),
        open_count(std::move(open)), unanswered_count(std::move(unanswered)), counters(std::move(c)) {
    ++*open_count;
  }
  ~Connection() { --*open_count; }

  // The next step (a line to come, or the reply to be taken) has kIdleMs; then the
  // connection is closed, which ends the pending read or write with an error.
  void arm(int ms = kIdleMs) {
    timer.expires_after(std::chrono::milliseconds(ms));
    timer.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
      if (ec) return;  // re-armed or cancelled
      ++self->counters->timed_out;
      boost::system::error_code ignored;
      self->socket.close(ignored);
    });
  }

  void read() {
    arm();
    auto self = shared_from_this();
    asio::async_read_until(socket, buffer, '\n', [self](const boost::system::error_code& ec, std::size_t n) {
      if (ec) {  // closed, timed out, or a line over kMaxLineBytes: the connection ends
        if (ec == asio::error::not_found) ++self->counters->too_long;
        self->timer.cancel();
        return;
      }
      std::string line(asio::buffers_begin(self->buffer.data()), asio::buffers_begin(self->buffer.data()) + n);
      self->buffer.consume(n);
      while (!line.empty() && (line.back() == '\n' || line.back() == '\r')) line.pop_back();
      if (line.empty()) return self->read();
      self->arm();
      ++*self->unanswered_count;  // until its reply is written (or the connection fails)
      if (self->deferred &&
          self->deferred(line, [self](std::string r) {
            asio::post(self->socket.get_executor(), [self, r = std::move(r)]() mutable { self->write(std::move(r)); });
          })) {
        self->arm(kDeferredMs);  // the answer comes from elsewhere (a database, a peer)
        return;
      }
      self->write(self->handle(line));
    });
  }

  void write(std::string text) {
    reply = std::move(text) + "\n";
    arm();
    auto self = shared_from_this();
    asio::async_write(socket, asio::buffer(reply), [self](const boost::system::error_code& e, std::size_t) {
      --*self->unanswered_count;
      if (!e) return self->read();
      self->timer.cancel();
    });
  }

  local::socket socket;
  asio::steady_timer timer;
  asio::streambuf buffer;
  std::string reply;
  std::function<std::string(const std::string&)>& handle;
  Deferred& deferred;
  std::shared_ptr<std::size_t> open_count;
  std::shared_ptr<std::size_t> unanswered_count;
  std::shared_ptr<Counters> counters;
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
    if (!ec && *open_ < kMaxConnections) {
      ++counters_->accepted;
      busy_logged_ = false;
      std::make_shared<Connection>(std::move(s), handle_, deferred_, open_, unanswered_, counters_)->read();
    } else if (!ec) {
      ++counters_->refused_busy;
      if (!busy_logged_)
        log_record(spdlog::level::warn, "console_busy", {{"open", *open_}, {"refused", counters_->refused_busy}});
      busy_logged_ = true;
      // A fresh socket's send buffer takes this line at once; the socket closes after it.
      static const std::string busy = R"({"ok":false,"error":"console busy: )" + std::to_string(kMaxConnections) +
                                      R"( connections open; try again"})" "\n";
      boost::system::error_code ignored;
      s.non_blocking(true, ignored);
      s.write_some(asio::buffer(busy), ignored);
    }
    accept();
  });
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
