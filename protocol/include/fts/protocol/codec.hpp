// Datagrams: the binary header followed by the payload, a list of messages encoded as
// JSON text or as MessagePack (the header's encoding field says which).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "fts/protocol/decoded.hpp"
#include "fts/protocol/header.hpp"
#include "fts/protocol/messages.hpp"

namespace fts::protocol {

struct Datagram {
  Header header;
  std::vector<Message> messages;
};

// Header + encoded messages. May exceed kMaxDatagramBytes: callers that build datagrams
// check the size (the endpoints do, and split snapshots to fit).
std::vector<std::uint8_t> encode_datagram(const Header& header, const std::vector<Message>& messages);

// Parses and validates a datagram; never throws, never reads past `bytes`.
Decoded<Datagram> decode_datagram(std::span<const std::uint8_t> bytes,
                                  std::uint16_t expected_version = kProtocolVersion);

// Decodes a datagram of any version if it holds exactly one Error message: how a client
// reads the "wrong version" refusal of a server that speaks another version.
// Such a refusal is the 19-byte header prefix and a JSON payload in every version.
Decoded<Error> decode_version_error(std::span<const std::uint8_t> bytes);
std::vector<std::uint8_t> encode_version_refusal(const Header& header, const Error& error);

// The payload alone, in one encoding (for size measurements and debugging).
std::vector<std::uint8_t> encode_payload(Encoding encoding, const std::vector<Message>& messages);
// Appends the payload to `out` (a reused buffer: no allocation once it is large enough).
void append_payload(Encoding encoding, const std::vector<Message>& messages, std::vector<std::uint8_t>& out);
// The payload's size without encoding it (MessagePack: counted by the same table code).
std::size_t payload_bytes(Encoding encoding, const std::vector<Message>& messages);
// The same two for a payload of one snapshot part, the server's per-client path: no
// message list is built (MessagePack allocates nothing once `out` has grown to size).
void append_snapshot_payload(Encoding encoding, const SnapshotMsg& part, std::vector<std::uint8_t>& out);
std::size_t snapshot_payload_bytes(Encoding encoding, const SnapshotMsg& part);
// Parses a payload alone (no header); never throws, never reads past `payload`.
Decoded<std::vector<Message>> decode_payload(Encoding encoding, std::span<const std::uint8_t> payload);
// JSON text of a message list, for logs and docs.
std::string to_json_text(const std::vector<Message>& messages);

}  // namespace fts::protocol
