// libFuzzer target: every byte string is a datagram from a hostile peer. The decoder
// must never crash, read out of bounds or throw; what decodes must re-encode to the same
// messages; the endpoints must survive it. Built by .ci/fuzz.sh (clang, -DFTS_FUZZ=ON).
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>

#include "fts/protocol/client.hpp"
#include "fts/protocol/codec.hpp"
#include "fts/protocol/server.hpp"
#include "fts/protocol/snapshot_delta.hpp"

using namespace fts::protocol;

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
  return 0;
}
