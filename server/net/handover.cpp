// The hand-over channel (handover.hpp): Asio TCP, libsodium's HMAC-SHA-256 and BLAKE2b.
#include "net/handover.hpp"

#include <sodium.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstring>
#include <deque>
#include <vector>

#include "app/handover_frame.hpp"
#include "app/log.hpp"
#include "fts/io/address.hpp"
#include "fts/room/json_fields.hpp"

namespace fts::server {

namespace asio = boost::asio;
using tcp = asio::ip::tcp;

namespace {

using namespace handover;
// A whole exchange, either side (up to 64 rooms; the console waits for a deferred reply
// up to net/console.hpp's kDeferredMs).
constexpr auto kDeadline = std::chrono::seconds(4);
// The peer's time to take a request's rooms, well inside the sender's kDeadline.
constexpr auto kAdoptBudget = std::chrono::seconds(2);
constexpr int kMaxDepth = 5;  // a request nests 4 deep (rooms, a room, its files, a file)

nlohmann::ordered_json refusal(const std::string& why) { return {{"ok", false}, {"error", why}}; }

// A key of a JSON object read without throwing: "" or 0 when absent or of another type.
std::string text_of(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_string() ? j[key].get<std::string>() : "";
}
std::int64_t int_of(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_number_integer() ? j[key].get<std::int64_t>() : 0;
}
bool true_at(const nlohmann::json& j, const char* key) {
  return j.is_object() && j.contains(key) && j[key].is_boolean() && j[key].get<bool>();
}

}  // namespace

struct HandoverChannel::Impl : std::enable_shared_from_this<HandoverChannel::Impl> {
  asio::io_context& io;
  GameHost& host;
  std::string key;
  std::uint16_t game_port;
  std::function<std::uint64_t()> now_ms;
  std::function<void()> flush;
  tcp::acceptor acceptor;
  bool closed = false;
  // Exchanges in flight, and those waiting their turn (their rooms play on meanwhile).
  // Rooms handed over together go in one exchange of up to kMaxRoomsPerExchange: one room
  // per exchange, 64 rooms took 4-10 s to move (each exchange's round trips waited for
  // two loaded loops); in one exchange 0.4-1.1 s (2026-12-07, BENCHMARKS.md).
  struct Waiting {
    std::vector<std::string> codes;
    std::string peer;
    HandoverChannel::EachDone each;
  };
  // Two exchanges at a time: when there was one room per exchange, 8 in flight ended the
  // 64-room move 5 % sooner but left each room frozen 3x longer while the peer worked
  // through the others (2026-12-06).
  std::deque<Waiting> waiting;
  std::size_t in_flight = 0;
  static constexpr std::size_t kMaxInFlight = 2;

  void start(Waiting w);
  void next() {
    while (in_flight < kMaxInFlight && !waiting.empty()) {
      Waiting w = std::move(waiting.front());
      waiting.pop_front();
      start(std::move(w));
    }
  }

  Impl(asio::io_context& i, GameHost& h, std::string k, std::uint16_t p, std::function<std::uint64_t()> n,
       std::function<void()> f)
      : io(i), host(h), key(std::move(k)), game_port(p), now_ms(std::move(n)), flush(std::move(f)), acceptor(i) {}

  // ---- the peer's side: one connection, one room.
  struct Inbound : std::enable_shared_from_this<Inbound> {
    std::shared_ptr<Impl> owner;
    tcp::socket socket;
    asio::steady_timer deadline;
    Bytes challenge = Bytes(kChallengeBytes);
    Bytes hello, body, reply;
    std::array<std::uint8_t, 4> length{};
    std::string from;
    nlohmann::json incoming;                                      // the request's rooms
    nlohmann::ordered_json adopted = nlohmann::ordered_json::array();  // an answer for each so far
    std::vector<std::string> taken;  // rooms answered ok: held here until the sender confirms them
    bool confirming = false;         // reading the confirmation: the first deadline is spent
    std::chrono::steady_clock::time_point adopt_until;

    Inbound(std::shared_ptr<Impl> o, tcp::socket s)
        : owner(std::move(o)), socket(std::move(s)), deadline(owner->io) {}

    void start() {
      boost::system::error_code ec;
      const auto ep = socket.remote_endpoint(ec);
      from = ec ? "?" : ep.address().to_string() + ":" + std::to_string(ep.port());
      randombytes_buf(challenge.data(), challenge.size());
      hello.assign(kMagic.begin(), kMagic.end());
      hello.insert(hello.end(), challenge.begin(), challenge.end());
      deadline.expires_after(kDeadline);
      // (Its handler may be queued already when the confirmation's wait re-arms the timer:
      // then it does nothing; the confirmation has its own deadline.)
      deadline.async_wait([self = shared_from_this()](const boost::system::error_code& e) {
        if (!e && !self->confirming) self->socket.close();
      });
      asio::async_write(socket, asio::buffer(hello), [self = shared_from_this()](auto e, std::size_t) {
        if (!e) self->read_length();
      });
    }
    void read_length() {
      asio::async_read(socket, asio::buffer(length), [self = shared_from_this()](auto e, std::size_t) {
        if (e) return;
        const std::uint32_t n = frame_length(self->length);
        if (n > kMaxFrameBytes) return self->answer(refusal("a request of " + std::to_string(n) + " bytes"), true);
        self->body.resize(n + kMacBytes);
        asio::async_read(self->socket, asio::buffer(self->body), [self](auto e2, std::size_t) {
          if (!e2) self->on_request();
        });
      });
    }
    void on_request() {
      const auto opened = open_body(owner->key, kRequestLabel, challenge, body);
      if (!opened) return answer(refusal("not authenticated: another fleet secret?"), true);
      std::string unread;
      auto parsed = room::parse_json(*opened, unread, kMaxDepth);
      if (!parsed || !parsed->is_object() || !parsed->contains("fts_handover"))
        return answer(refusal("not a hand-over request: " + unread), true);
      const nlohmann::json& req = *parsed;
      // The version first: another version's request may be shaped otherwise.
      if (text_of(req, "version") != FTS_VERSION)
        return answer(refusal("another version: this server runs " + std::string(FTS_VERSION) +
                              ", the room comes from " + text_of(req, "version")),
                      true);
      if (int_of(req, "fts_handover") != kFormat || !req.contains("rooms") || !req["rooms"].is_array() ||
          req["rooms"].empty() || req["rooms"].size() > kMaxRoomsPerExchange)
        return answer(refusal("not a hand-over request of format " + std::to_string(kFormat) + " (1 to " +
                              std::to_string(kMaxRoomsPerExchange) + " rooms)"),
                      true);
      incoming = std::move((*parsed)["rooms"]);  // the segments: not copied
      adopt_until = std::chrono::steady_clock::now() + kAdoptBudget;
      adopt_next();
    }
    // One room per turn of the loop, so the peer's own rooms tick between them; rooms
    // left when the budget is spent are refused (the sender keeps them) well before the
    // sender gives up on the answer, which would leave a room running on both servers.
    void adopt_next() {
      if (adopted.size() == incoming.size()) {
        owner->flush();
        return answer({{"ok", true}, {"port", owner->game_port}, {"rooms", std::move(adopted)}}, false);
      }
      const nlohmann::json& entry = incoming[adopted.size()];
      if (std::chrono::steady_clock::now() > adopt_until)
        adopted.push_back({{"room", text_of(entry, "room")}, {"ok", false}, {"error", "out of time for more rooms"}});
      else
        adopted.push_back(adopt(entry));
      owner->flush();
      asio::post(owner->io, [self = shared_from_this()] { self->adopt_next(); });
    }
    // One room of a request: {"room","ok":true,"tick"} or {"room","ok":false,"error"}.
    nlohmann::ordered_json adopt(const nlohmann::json& entry) {
      const std::string code = text_of(entry, "room");
      auto refused = [&](const std::string& why) {
        return nlohmann::ordered_json{{"room", code}, {"ok", false}, {"error", why}};
      };
      if (code.empty() || !entry.contains("files") || !entry["files"].is_array())
        return refused("a room of the request is not {room, tick, files}");
      std::vector<std::pair<std::string, std::string>> files;
      for (const auto& f : entry["files"]) {
        if (!f.is_object() || !f.contains("name") || !f["name"].is_string() || !f.contains("text") ||
            !f["text"].is_string())
          return refused("a file of the request is not {name, text}");
        files.emplace_back(f["name"].get<std::string>(), f["text"].get<std::string>());
      }
      if (const std::string why = owner->host.adopt_room(code, files, owner->now_ms()); !why.empty())
        return refused(why);
      taken.push_back(code);
      const Room* r = owner->host.room_by_code(code);
      return {{"room", code}, {"ok", true}, {"tick", r ? r->match().tick : 0}};
    }
    void answer(const nlohmann::ordered_json& j, bool unauthenticated) {
      if (unauthenticated)
        log_record(spdlog::level::warn, "handover_denied", {{"from", from}, {"reason", j.value("error", std::string())}});
      reply = frame(owner->key, kReplyLabel, challenge, j.dump());
      asio::async_write(socket, asio::buffer(reply), [self = shared_from_this()](auto e, std::size_t) {
        if (!self->taken.empty()) {
          if (!e) return self->read_confirm();
          return self->unconfirmed("the answer could not be written: " + e.message());
        }
        self->close();
      });
    }
    // Step 4: the sender confirms the rooms it will tell to come here. Rooms taken and not
    // confirmed stay held (GameHost::confirm_adopted): a client of one that arrives
    // confirms it, else it is forgotten (the sender kept it: a copy must not live on here).
    void read_confirm() {
      confirming = true;
      deadline.expires_after(kDeadline);
      deadline.async_wait([self = shared_from_this()](const boost::system::error_code& e) {
        if (!e) self->socket.close();
      });
      asio::async_read(socket, asio::buffer(length), [self = shared_from_this()](auto e, std::size_t) {
        if (e) return self->unconfirmed("the sender closed the connection before confirming");
        const std::uint32_t n = frame_length(self->length);
        if (n > kMaxFrameBytes) return self->unconfirmed("a confirmation of " + std::to_string(n) + " bytes");
        self->body.resize(n + kMacBytes);
        asio::async_read(self->socket, asio::buffer(self->body), [self](auto e2, std::size_t) {
          if (e2) return self->unconfirmed("the sender closed the connection before confirming");
          self->on_confirm();
        });
      });
    }
    void on_confirm() {
      const auto opened = open_body(owner->key, kConfirmLabel, challenge, body);
      if (!opened) return unconfirmed("the confirmation is not authentic");
      std::string why;
      const auto parsed = room::parse_json(*opened, why, kMaxDepth);
      if (!parsed || !parsed->is_object() || int_of(*parsed, "fts_handover_confirm") != kFormat ||
          !parsed->contains("rooms") || !(*parsed)["rooms"].is_array())
        return unconfirmed("not a confirmation: " + why);
      for (const auto& r : (*parsed)["rooms"])
        if (r.is_string() && std::find(taken.begin(), taken.end(), r.get<std::string>()) != taken.end())
          owner->host.confirm_adopted(r.get<std::string>(), "sender");
      // (A room's player may have come first, told by the sender: confirmed already.)
      const auto confirmed = static_cast<std::size_t>(std::count_if(
          taken.begin(), taken.end(), [&](const std::string& code) { return !owner->host.unconfirmed(code); }));
      if (confirmed < taken.size())
        log_record(spdlog::level::warn, "handover_unconfirmed",
                   {{"from", from}, {"rooms", taken.size() - confirmed}, {"reason", "the sender did not confirm them"}});
      close();
    }
    void unconfirmed(const std::string& why) {
      log_record(spdlog::level::warn, "handover_unconfirmed", {{"from", from}, {"rooms", taken.size()}, {"reason", why}});
      close();
    }
    void close() {
      boost::system::error_code ignored;
      socket.shutdown(tcp::socket::shutdown_both, ignored);
      deadline.cancel();
    }
  };

  void accept() {
    acceptor.async_accept([self = shared_from_this()](const boost::system::error_code& e, tcp::socket s) {
      if (e || self->closed) return;
      std::make_shared<Inbound>(self, std::move(s))->start();
      self->accept();
    });
  }

  // ---- the sender's side: one connection, the rooms of one exchange.
  struct Outbound : std::enable_shared_from_this<Outbound> {
    struct Moving {
      std::string code;
      std::int64_t tick = 0;
      bool finished = false;
    };
    std::shared_ptr<Impl> owner;
    std::string peer_host, peer;
    std::vector<Moving> rooms;
    EachDone each;
    tcp::resolver resolver;
    tcp::socket socket;
    asio::steady_timer deadline;
    std::array<std::uint8_t, kMagic.size() + kChallengeBytes> hello{};
    Bytes challenge, request, body;
    std::array<std::uint8_t, 4> length{};
    std::chrono::steady_clock::time_point started = std::chrono::steady_clock::now();
    bool finished = false;
    // The confirmation is being written: no room may be kept from now on (it may reach
    // the peer whatever happens next), so the first deadline's handler, if it was queued
    // already when the reply came, does nothing.
    bool confirming = false;

    Outbound(std::shared_ptr<Impl> o, std::string p, EachDone e)
        : owner(std::move(o)), peer(std::move(p)), each(std::move(e)), resolver(owner->io), socket(owner->io),
          deadline(owner->io) {}

    void start(std::vector<GameHost::RoomExport> exports, const fts::io::HostPort& hp) {
      peer_host = hp.host;
      nlohmann::json req = {{"fts_handover", kFormat}, {"version", FTS_VERSION}, {"rooms", nlohmann::json::array()}};
      for (auto& ex : exports) {
        rooms.push_back({ex.code, ex.tick, false});
        nlohmann::json room = {{"room", ex.code}, {"tick", ex.tick}, {"files", nlohmann::json::array()}};
        for (auto& [name, text] : ex.files) room["files"].push_back({{"name", name}, {"text", std::move(text)}});
        req["rooms"].push_back(std::move(room));
      }
      const std::string json = req.dump();
      request.assign(json.begin(), json.end());  // framed once the challenge is known
      deadline.expires_after(kDeadline);
      deadline.async_wait([self = shared_from_this()](const boost::system::error_code& e) {
        if (!e && !self->confirming) self->fail("no answer from the peer " + self->peer + " in 4 s");
      });
      resolver.async_resolve(hp.host, hp.port, [self = shared_from_this()](auto e, tcp::resolver::results_type r) {
        if (e) return self->fail("cannot resolve the peer " + self->peer + ": " + e.message());
        asio::async_connect(self->socket, r, [self](auto e2, const tcp::endpoint&) {
          if (e2) return self->fail("cannot reach the peer " + self->peer + ": " + e2.message());
          asio::async_read(self->socket, asio::buffer(self->hello), [self](auto e3, std::size_t) {
            if (e3) return self->fail("the peer " + self->peer + " closed the connection: " + e3.message());
            if (std::memcmp(self->hello.data(), kMagic.data(), kMagic.size()) != 0)
              return self->fail("the peer " + self->peer + " does not take rooms (not an fts-server's --handover-listen)");
            self->challenge.assign(self->hello.begin() + kMagic.size(), self->hello.end());
            const std::string json(self->request.begin(), self->request.end());
            self->request = frame(self->owner->key, kRequestLabel, self->challenge, json);
            asio::async_write(self->socket, asio::buffer(self->request), [self](auto e4, std::size_t) {
              if (e4) return self->fail("the peer " + self->peer + " closed the connection: " + e4.message());
              self->read_reply();
            });
          });
        });
      });
    }
    void read_reply() {
      asio::async_read(socket, asio::buffer(length), [self = shared_from_this()](auto e, std::size_t) {
        if (e) return self->fail("the peer " + self->peer + " closed the connection before answering");
        const std::uint32_t n = frame_length(self->length);
        if (n > kMaxFrameBytes) return self->fail("the peer's answer is too long");
        self->body.resize(n + kMacBytes);
        asio::async_read(self->socket, asio::buffer(self->body), [self](auto e2, std::size_t) {
          if (e2) return self->fail("the peer " + self->peer + " closed the connection before answering");
          self->on_reply();
        });
      });
    }
    void on_reply() {
      if (finished) return;  // the deadline came first: every room was kept
      const auto opened = open_body(owner->key, kReplyLabel, challenge, body);
      if (!opened) return fail("the peer " + peer + "'s answer is not authentic: it holds another fleet secret");
      std::string why;
      const auto parsed = room::parse_json(*opened, why, kMaxDepth);
      if (!parsed || !parsed->is_object()) return fail("the peer's answer is not a JSON object: " + why);
      const nlohmann::json& reply = *parsed;
      if (!true_at(reply, "ok")) return fail("the peer " + peer + " refused: " + text_of(reply, "error"));
      const auto port = int_of(reply, "port");
      if (port <= 0 || port > 65535) return fail("the peer's answer names no game port");
      const std::string address = fts::io::host_port_text(peer_host, static_cast<unsigned>(port));
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
      const nlohmann::json none = nlohmann::json::object();
      nlohmann::json taken = nlohmann::json::array();
      for (auto& room : rooms) {
        const nlohmann::json* answer = &none;
        if (reply.contains("rooms") && reply["rooms"].is_array())
          for (const auto& r : reply["rooms"])
            if (text_of(r, "room") == room.code) answer = &r;
        if (!true_at(*answer, "ok")) {
          const std::string error = text_of(*answer, "error");
          keep(room, "the peer " + peer + " refused: " + (error.empty() ? "no answer for the room" : error));
          continue;
        }
        taken.push_back(room.code);
      }
      if (taken.empty()) return finish();
      confirming = true;
      // Step 4: confirm the rooms taken, and only once the confirmation is written tell
      // their clients. From here the deadline only closes the socket (the write then
      // fails and the rooms stay): a confirmation may reach the peer whatever happens
      // after it is written, so no room is kept once it has been.
      deadline.expires_after(kDeadline);
      deadline.async_wait([self = shared_from_this()](const boost::system::error_code& e) {
        if (!e) self->socket.close();
      });
      const nlohmann::json confirm = {{"fts_handover_confirm", kFormat}, {"rooms", std::move(taken)}};
      request = frame(owner->key, kConfirmLabel, challenge, confirm.dump());
      asio::async_write(socket, asio::buffer(request), [self = shared_from_this(), address, ms](auto e, std::size_t) {
        // Not written whole: the peer cannot have read it, and forgets the rooms it holds.
        if (e) return self->fail("the confirmation to the peer " + self->peer + " failed: " + e.message());
        for (auto& room : self->rooms) {
          if (room.finished) continue;
          room.finished = true;
          const std::size_t told = self->owner->host.room_moved(room.code, address, self->owner->now_ms());
          self->each(room.code, {{"ok", true}, {"room", room.code}, {"to", address}, {"tick", room.tick},
                                 {"clients_told", told}, {"ms", ms}});
        }
        self->owner->flush();
        self->finish();
      });
    }
    void keep(Moving& room, const std::string& why) {
      if (room.finished) return;
      room.finished = true;
      owner->host.room_kept(room.code, why);
      each(room.code, refusal(why + "; room " + room.code + " plays on here"));
    }
    void fail(const std::string& why) {
      if (finished) return;
      for (auto& room : rooms) keep(room, why);
      finish();
    }
    void finish() {
      if (finished) return;
      finished = true;
      deadline.cancel();
      boost::system::error_code ignored;
      socket.close(ignored);
      --owner->in_flight;
      owner->next();
    }
  };
};

void HandoverChannel::Impl::start(Waiting w) {
  const auto hp = fts::io::parse_host_port(w.peer);
  if (!hp) {
    for (const auto& code : w.codes)
      w.each(code, refusal("the peer must be HOST:PORT (its --handover-listen), got \"" + w.peer + "\""));
    return;
  }
  auto exported = host.export_rooms(w.codes);
  std::vector<GameHost::RoomExport> exports;
  for (std::size_t i = 0; i < exported.size(); ++i) {
    if (auto* why = std::get_if<std::string>(&exported[i])) w.each(w.codes[i], refusal(*why));
    else exports.push_back(std::move(std::get<GameHost::RoomExport>(exported[i])));
  }
  if (exports.empty()) return;
  ++in_flight;
  std::make_shared<Outbound>(shared_from_this(), std::move(w.peer), std::move(w.each))->start(std::move(exports), *hp);
}

HandoverChannel::HandoverChannel(asio::io_context& io, GameHost& host, std::string key, std::uint16_t game_port,
                                 std::function<std::uint64_t()> now_ms, std::function<void()> flush)
    : impl_(std::make_shared<Impl>(io, host, std::move(key), game_port, std::move(now_ms), std::move(flush))) {}

HandoverChannel::~HandoverChannel() {
  impl_->closed = true;
  boost::system::error_code ignored;
  impl_->acceptor.close(ignored);
}

std::string HandoverChannel::listen(const std::string& address) {
  const auto hp = fts::io::parse_host_port(address);
  if (!hp) return "--handover-listen: not ADDR:PORT: " + address;
  boost::system::error_code ec;
  const auto ip = asio::ip::make_address(hp->host, ec);
  if (ec) return "--handover-listen: not an IP address: " + hp->host;
  const tcp::endpoint ep(ip, static_cast<std::uint16_t>(std::stoi(hp->port)));
  auto& a = impl_->acceptor;
  if (a.open(ep.protocol(), ec); ec) return "--handover-listen: " + ec.message();
  a.set_option(tcp::acceptor::reuse_address(true), ec);
  if (a.bind(ep, ec); ec) return "--handover-listen: cannot bind " + address + ": " + ec.message();
  if (a.listen(16, ec); ec) return "--handover-listen: " + ec.message();
  impl_->accept();
  return "";
}

std::uint16_t HandoverChannel::port() const {
  boost::system::error_code ec;
  const auto ep = impl_->acceptor.local_endpoint(ec);
  return ec ? 0 : ep.port();
}

void HandoverChannel::hand_over(const std::string& code, const std::string& peer, Done done) {
  hand_over(std::vector<std::string>{code}, peer, [done = std::move(done)](const std::string&, nlohmann::ordered_json j) {
    done(std::move(j));
  });
}

void HandoverChannel::hand_over(const std::vector<std::string>& codes, const std::string& peer, EachDone each) {
  for (std::size_t i = 0; i < codes.size(); i += kMaxRoomsPerExchange) {
    const auto end = codes.begin() + static_cast<std::ptrdiff_t>(std::min(codes.size(), i + kMaxRoomsPerExchange));
    impl_->waiting.push_back({{codes.begin() + static_cast<std::ptrdiff_t>(i), end}, peer, each});
  }
  impl_->next();
}

}  // namespace fts::server
