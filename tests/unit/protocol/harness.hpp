// A server endpoint and several client endpoints joined by lossy links, stepped by hand.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fts/protocol/client.hpp"
#include "fts/protocol/connection.hpp"
#include "fts/protocol/server.hpp"
#include "lossy_link.hpp"

namespace fts::protocol::test {

inline ServerKey test_key() {
  ServerKey k{};
  for (std::size_t i = 0; i < k.size(); ++i) k[i] = static_cast<std::uint8_t>(i * 7 + 1);
  return k;
}

// The client's channel, or the server's side of it (as_server): fresh sequence state.
inline SealedChannel channel_of(const ClientEndpoint& client, bool as_server = false) {
  const SessionKeys& k = client.session_keys();
  return as_server ? SealedChannel(SessionKeys{k.tx, k.rx}, SealDirection::server_to_client,
                                   SealDirection::client_to_server)
                   : SealedChannel(k, SealDirection::client_to_server, SealDirection::server_to_client);
}

// A datagram from the server to this client, opened with the client's keys (a fresh
// replay window each time: any datagram, any number of times). A handshake datagram
// (session 0) is decoded as it is.
inline Decoded<Datagram> peek(const ClientEndpoint& client, std::span<const std::uint8_t> bytes) {
  auto h = read_header_any_version(bytes);
  if (!h || h->session == 0) return decode_datagram(bytes);
  SealedChannel channel = channel_of(client);
  std::vector<std::uint8_t> plain;
  return open_sealed(channel, bytes, kProtocolVersion, plain);
}

// A datagram on the client's session with a header a script chose, sealed with the
// client's keys as a hostile but keyed client would (extended sequence = header.sequence);
// as_server: as the server would seal it for the client.
inline std::vector<std::uint8_t> seal_as(const ClientEndpoint& client, const Header& header,
                                         const std::vector<Message>& messages, bool as_server = false) {
  SealedChannel channel = channel_of(client, as_server);
  return encode_sealed(channel, header, messages);
}
// The same with any payload bytes (garbage that only a keyed peer can make reach the parser).
inline std::vector<std::uint8_t> seal_raw(const ClientEndpoint& client, const Header& header,
                                          const std::string& payload, bool as_server = false) {
  SealedChannel channel = channel_of(client, as_server);
  std::vector<std::uint8_t> out;
  channel.seal(header, std::span(reinterpret_cast<const std::uint8_t*>(payload.data()), payload.size()), out);
  return out;
}

// A client config with this name (and a session token to resume with).
inline ClientConfig named(const std::string& name, const std::string& token = "") {
  ClientConfig c;
  c.name = name;
  c.token = token;
  return c;
}

inline ServerConfig test_server_config() {
  ServerConfig c;
  c.key = test_key();
  return c;
}

// The host's part in these tests: one room (1) of max_players seats, whatever the hello
// asks for; a full room answers server_full. `server` is read only when a hello comes, so
// an endpoint may be handed its own config: ServerEndpoint s(one_room(config, s)).
inline ServerConfig one_room(ServerConfig config, const ServerEndpoint& server) {
  const std::uint32_t seats = config.max_players;
  config.admit = [&server, seats](const JoinAsk&) {
    Admission a;
    if (server.seats_in_room(1) >= seats) {
      a.error = ErrorCode::server_full;
      a.message = "the server is full (" + std::to_string(seats) + " players); try again later";
    } else {
      a.room = 1;
    }
    return a;
  };
  return config;
}

struct Peer {
  std::string address;
  ClientEndpoint client;
  LossyLink up;    // client -> server
  LossyLink down;  // server -> client
};

// A rig of one ClientConnection (its `conn`, its clock `now`, its step()): steps it until
// pred holds or for_ms of its time has passed; and whether the connection is welcomed.
template <class Rig, class Pred>
bool step_until(Rig& rig, Pred pred, std::uint64_t for_ms) {
  const std::uint64_t deadline = rig.now + for_ms;
  while (!pred() && rig.now < deadline) rig.step();
  return pred();
}
inline bool welcomed(const ClientConnection& conn) {
  return conn.state() == ClientState::connected && conn.endpoint().welcome();
}

class Harness {
 public:
  explicit Harness(ServerConfig config = test_server_config()) : server(one_room(std::move(config), server)) {}

  Peer& add_client(ClientConfig config, LinkConfig link = {}, std::string address = "") {
    if (address.empty()) address = "10.0.0." + std::to_string(peers.size() + 1) + ":5000";
    LinkConfig down = link;
    down.seed = link.seed * 31 + 7;
    peers.push_back(std::make_unique<Peer>(Peer{address, ClientEndpoint(config), LossyLink(link), LossyLink(down)}));
    return *peers.back();
  }

  // Moves every datagram due at `now`, then runs the timers; returns nothing.
  void step(std::uint64_t now_ms) {
    now = now_ms;
    for (auto& p : peers) {
      for (auto& bytes : p->client.take_datagrams()) p->up.send(std::move(bytes), now);
      for (auto& bytes : p->up.receive(now)) server.receive(p->address, bytes, now);
    }
    for (auto& out : server.take_datagrams()) {
      for (auto& p : peers)
        if (p->address == out.to) p->down.send(out.bytes, now);
    }
    for (auto& p : peers) {
      for (auto& bytes : p->down.receive(now)) p->client.receive(bytes, now);
      p->client.update(now);
    }
    server.update(now);
  }

  // Steps in 5 ms increments until pred() or the deadline; returns pred().
  template <class Pred>
  bool run_until(Pred pred, std::uint64_t deadline_ms) {
    while (now < deadline_ms) {
      step(now + 5);
      if (pred()) return true;
    }
    return pred();
  }

  ServerEndpoint server;
  std::vector<std::unique_ptr<Peer>> peers;
  std::uint64_t now = 100;
};

inline bool connected(const Peer& p) { return p.client.state() == ClientState::connected; }

}  // namespace fts::protocol::test
