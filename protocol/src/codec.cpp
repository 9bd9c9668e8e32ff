#include "fts/protocol/codec.hpp"

#include <array>
#include <utility>

#include "json_reader.hpp"
#include "specs.hpp"

namespace fts::protocol {

namespace {

template <class W, class M>
void write_one(W& w, const M& msg) {
  wire::write_map(w, wire::Spec<M>::type.data(), msg, wire::Spec<M>::fields());
}

template <class W>
void write_message(W& w, const Message& m) {
  std::visit([&w](const auto& msg) { write_one(w, msg); }, m);
}

template <class W>
void write_messages(W& w, const std::vector<Message>& messages) {
  w.array(messages.size());
  for (const auto& m : messages) write_message(w, m);
}

template <class M>
Decoded<Message> read_as(wire::MsgpackReader& r) {
  M m;
  wire::read_map(r, m, wire::Spec<M>::fields());
  wire::check(r, m);
  if (r.failed()) return r.reason();
  return Message{std::move(m)};
}

// One reader per message type, in variant order, found by its wire name.
struct Reader {
  std::string_view type;
  Decoded<Message> (*read)(wire::MsgpackReader&);
};
template <std::size_t... I>
constexpr auto make_readers(std::index_sequence<I...>) {
  return std::array<Reader, sizeof...(I)>{
      Reader{wire::Spec<std::variant_alternative_t<I, Message>>::type, &read_as<std::variant_alternative_t<I, Message>>}...};
}
constexpr auto kReaders = make_readers(std::make_index_sequence<std::variant_size_v<Message>>{});

// One message (a map) at the reader's position: its "t" first (our writers put it first,
// so usually the first key), then the table of that type reads it from the start.
Decoded<Message> read_message(wire::MsgpackReader& r) {
  const std::size_t start = r.pos();
  const std::size_t n = r.map(kMaxPayloadValues);
  std::string_view type;
  bool typed = false;
  for (std::size_t i = 0; i < n && !r.failed() && !typed; ++i) {
    const std::string_view key = r.str(kMaxTextBytes);
    if (key == "t" && !r.failed()) {
      type = r.str(kMaxTextBytes);
      typed = !r.failed();
    } else {
      r.skip();
    }
  }
  if (r.failed() || !typed) return Reject::garbage;
  for (const Reader& reader : kReaders) {
    if (reader.type != type) continue;
    r.seek(start);
    return reader.read(r);
  }
  return Reject::unknown_type;
}

Decoded<std::vector<Message>> decode_msgpack(std::span<const std::uint8_t> payload) {
  if (payload.empty()) return Reject::truncated;
  wire::MsgpackReader r(payload);
  r.validate_value();
  if (r.failed()) return r.reason() == Reject::out_of_range ? Reject::out_of_range : Reject::garbage;
  const std::size_t n = r.array(kMaxPayloadValues);
  if (r.failed() || n == 0) return Reject::garbage;
  if (n > kMaxMessagesPerDatagram) return Reject::out_of_range;
  std::vector<Message> messages;
  messages.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    auto m = read_message(r);
    if (!m) return m.error();
    messages.push_back(std::move(*m));
  }
  if (!r.at_end()) return Reject::garbage;  // bytes after the list
  return messages;
}

// JSON text: nlohmann's SAX parser writes it as MessagePack, which the tables read.
Decoded<std::vector<Message>> decode_json(std::span<const std::uint8_t> payload) {
  if (payload.empty()) return Reject::truncated;
  std::vector<std::uint8_t> packed;
  packed.reserve(payload.size());
  Reject why = Reject::garbage;
  if (!wire::json_to_msgpack(payload, packed, why)) return why;
  return decode_msgpack(packed);
}

}  // namespace

Decoded<std::vector<Message>> decode_payload(Encoding encoding, std::span<const std::uint8_t> payload) {
  return encoding == Encoding::json ? decode_json(payload) : decode_msgpack(payload);
}

std::vector<std::uint8_t> encode_payload(Encoding encoding, const std::vector<Message>& messages) {
  std::vector<std::uint8_t> out;
  append_payload(encoding, messages, out);
  return out;
}

namespace {
// `write(w)` with the writer of the encoding, appended to `out` / counted.
template <class Write>
void append_encoded(Encoding encoding, std::vector<std::uint8_t>& out, Write write) {
  if (encoding == Encoding::msgpack) {
    wire::MsgpackWriter w(out);
    return write(w);
  }
  std::string text;
  wire::JsonWriter w(text);
  write(w);
  out.insert(out.end(), text.begin(), text.end());
}
template <class Write>
std::size_t count_encoded(Encoding encoding, Write write) {
  if (encoding == Encoding::msgpack) {
    wire::MsgpackCounter c;
    write(c);
    return c.bytes;
  }
  std::string text;
  wire::JsonWriter w(text);
  write(w);
  return text.size();
}
}  // namespace

void append_payload(Encoding encoding, const std::vector<Message>& messages, std::vector<std::uint8_t>& out) {
  append_encoded(encoding, out, [&](auto& w) { write_messages(w, messages); });
}

std::size_t payload_bytes(Encoding encoding, const std::vector<Message>& messages) {
  return count_encoded(encoding, [&](auto& w) { write_messages(w, messages); });
}

void append_snapshot_payload(Encoding encoding, const SnapshotMsg& part, std::vector<std::uint8_t>& out) {
  append_encoded(encoding, out, [&](auto& w) {
    w.array(1);
    write_one(w, part);
  });
}

std::size_t snapshot_payload_bytes(Encoding encoding, const SnapshotMsg& part) {
  return count_encoded(encoding, [&](auto& w) {
    w.array(1);
    write_one(w, part);
  });
}

const char* message_type(const Message& message) {
  return std::visit([](const auto& m) { return wire::Spec<std::decay_t<decltype(m)>>::type.data(); }, message);
}

std::string to_json_text(const std::vector<Message>& messages) {
  std::string text;
  wire::JsonWriter w(text);
  write_messages(w, messages);
  return text;
}

std::vector<std::uint8_t> encode_datagram(const Header& header, const std::vector<Message>& messages) {
  std::vector<std::uint8_t> out;
  out.reserve(256);
  write_header(header, out);
  append_payload(header.encoding, messages, out);
  return out;
}

Decoded<Datagram> decode_datagram(std::span<const std::uint8_t> bytes, std::uint16_t expected_version) {
  auto header = read_header(bytes, expected_version);
  if (!header) return header.error();
  auto messages = decode_payload(header->encoding, bytes.subspan(kHeaderBytes));
  if (!messages) return messages.error();
  return Datagram{*header, std::move(*messages)};
}

std::vector<std::uint8_t> encode_version_refusal(const Header& header, const Error& error) {
  std::vector<std::uint8_t> out;
  Header h = header;
  h.encoding = Encoding::json;
  write_header_prefix(h, out);
  const auto payload = encode_payload(Encoding::json, {error});
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

Decoded<Error> decode_version_error(std::span<const std::uint8_t> bytes) {
  auto header = read_header_any_version(bytes);
  if (!header) return header.error();
  auto messages = decode_payload(header->encoding, bytes.subspan(kHeaderPrefixBytes));
  if (!messages) return messages.error();
  if (messages->size() != 1 || !std::holds_alternative<Error>(messages->front()))
    return Reject::unexpected;
  return std::get<Error>(messages->front());
}

}  // namespace fts::protocol
