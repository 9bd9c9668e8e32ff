// libFuzzer target: every byte string is a datagram from a hostile peer. The decoder
// must never crash, read out of bounds or throw; what decodes must re-encode to the same
// messages; the endpoints must survive it. The sealed framing (PROTOCOL.md 5.7) twice:
// the bytes as a datagram on a live session (header, replay window, tag), and the bytes
// as a payload sealed with the session's keys, so that they reach the parser and the
// session's state. Built by .ci/fuzz.sh (clang, -DFTS_FUZZ=ON).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "fts/protocol/client.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/seal.hpp"
#include "fts/protocol/server.hpp"
#include "fts/protocol/snapshot_delta.hpp"

using namespace fts::protocol;

namespace {

// The host's part: every new player goes to room 1 (seats are the host's business).
Admission room_one(const JoinAsk&) {
  Admission a;
  a.room = 1;
  return a;
}

ServerConfig fuzz_server_config() {
  ServerConfig config;
  config.admit = room_one;
  for (std::size_t i = 0; i < config.key.size(); ++i) config.key[i] = static_cast<std::uint8_t>(i);
  config.session_datagrams_per_s = config.session_datagram_burst = 1'000'000;
  config.address_datagrams_per_s = config.address_datagram_burst = 1'000'000;
  return config;
}

// A server with one connected client, made again whenever the fuzz input ended it.
struct Live {
  ServerEndpoint server{fuzz_server_config()};
  ClientEndpoint client;
  const Address address = "10.1.1.1:7";
  std::uint64_t now_ms = 1000;
  std::uint32_t session = 0;
  std::uint16_t sequence = 100;

  bool connect() {
    client.connect(now_ms);
    for (int i = 0; i < 20 && client.state() != ClientState::connected; ++i) {
      for (auto& d : client.take_datagrams()) server.receive(address, d, now_ms);
      for (auto& o : server.take_datagrams()) client.receive(o.bytes, now_ms);
      now_ms += 5;
    }
    client.send_input({}, now_ms);
    const auto out = client.take_datagrams();
    if (client.state() != ClientState::connected || out.empty()) return false;
    session = read_header(out.back())->session;
    return true;
  }
};

void fuzz_sealed(std::span<const std::uint8_t> bytes) {
  static Live* live = nullptr;
  if (!live || live->server.connected_players().empty()) {
    delete live;
    live = new Live;
    if (!live->connect()) std::abort();
  }
  live->now_ms += 3;
  // The bytes as a whole datagram from the session's address: never opened.
  live->server.receive(live->address, bytes, live->now_ms);
  // The bytes as a payload, sealed with the client's keys (either encoding): they open,
  // and reach the parser and the session.
  Header h;
  h.session = live->session;
  h.sequence = ++live->sequence == 0 ? ++live->sequence : live->sequence;
  h.encoding = !bytes.empty() && (bytes[0] & 1) ? Encoding::msgpack : Encoding::json;
  SealedChannel channel(live->client.session_keys(), SealDirection::client_to_server,
                        SealDirection::server_to_client);
  std::vector<std::uint8_t> datagram;
  channel.seal(h, bytes, datagram);
  live->server.receive(live->address, datagram, live->now_ms);
  // And as the server's datagram to the client, sealed with the server's side of the keys.
  const SessionKeys& k = live->client.session_keys();
  SealedChannel from_server(SessionKeys{k.tx, k.rx}, SealDirection::server_to_client,
                            SealDirection::client_to_server);
  datagram.clear();
  from_server.seal(h, bytes, datagram);
  live->client.receive(datagram, live->now_ms);
  live->client.receive(bytes, live->now_ms);
  live->server.update(live->now_ms);
  (void)live->server.take_datagrams();
  (void)live->server.take_events();
  (void)live->server.take_inputs();
  (void)live->server.take_commands();
  (void)live->client.take_datagrams();
  // The sequence arithmetic on arbitrary values.
  if (bytes.size() >= 10) {
    std::uint64_t newest = 0;
    for (int i = 0; i < 8; ++i) newest = (newest << 8) | bytes[2 + i];
    const std::uint16_t wire = static_cast<std::uint16_t>((bytes[0] << 8) | bytes[1]);
    const std::uint64_t ext = extend_sequence(wire, newest);
    if ((ext & 0xFFFF) != wire) std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);

  auto d = decode_datagram(bytes);
  if (d) {
    auto again = decode_datagram(encode_datagram(d->header, d->messages));
    // A decoded datagram may re-encode larger than 1200 bytes only if it was near the limit.
    if (again && !(again->messages == d->messages)) std::abort();
    SnapshotReceiver rx;
    for (const auto& m : d->messages)
      if (const auto* s = std::get_if<SnapshotMsg>(&m)) (void)rx.accept(*s);
  }
  (void)decode_version_error(bytes);
  // The payload decoders alone (the field-table readers, bit-packed motion entries
  // included): what decodes re-encodes to bytes that decode to the same messages.
  for (auto enc : {Encoding::msgpack, Encoding::json}) {
    auto p = decode_payload(enc, bytes);
    if (!p) continue;
    auto again = decode_payload(enc, encode_payload(enc, *p));
    if (!again || !(*again == *p)) std::abort();
  }

  // The server, before and after a client is connected, and a client in each state.
  static ServerEndpoint* server = [] {
    ServerConfig config;
    config.admit = room_one;
    for (std::size_t i = 0; i < config.key.size(); ++i) config.key[i] = static_cast<std::uint8_t>(i);
    return new ServerEndpoint(config);
  }();
  static std::uint64_t now_ms = 1000;
  now_ms += 7;
  server->receive("1.2.3.4:5", bytes, now_ms);
  server->update(now_ms);
  (void)server->take_datagrams();
  (void)server->take_events();
  (void)server->take_inputs();
  (void)server->take_commands();

  ClientEndpoint client;
  client.connect(now_ms);
  client.receive(bytes, now_ms);
  client.update(now_ms + 300);
  (void)client.take_datagrams();

  fuzz_sealed(bytes);
  return 0;
}
