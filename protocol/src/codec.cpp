#include "fts/protocol/codec.hpp"

#include "mapping.hpp"
#include "tables.hpp"

namespace fts::protocol {

using nlohmann::json;

namespace {

json messages_to_json(const std::vector<Message>& messages) {
  json array = json::array();
  for (const auto& m : messages) array.push_back(message_to_json(m));
  return array;
}

std::string dump(const json& j) {
  return j.dump(-1, ' ', false, json::error_handler_t::replace);
}

// nlohmann's tree builder behind a gate: parsing stops at the first array or object
// nested deeper than kMaxNestingDepth, the first container that claims more elements
// than the payload has bytes (MessagePack states its sizes), or value number
// kMaxPayloadValues + 1. A hostile payload costs one partial pass over its bytes and
// never builds a deep tree (PROTOCOL.md 10).
class BoundedSax {
 public:
  using number_integer_t = json::number_integer_t;
  using number_unsigned_t = json::number_unsigned_t;
  using number_float_t = json::number_float_t;
  using string_t = json::string_t;
  using binary_t = json::binary_t;

  BoundedSax(json& root, std::size_t payload_bytes) : dom_(root, /*allow_exceptions=*/false), bytes_(payload_bytes) {}

  bool null() { return value() && dom_.null(); }
  bool boolean(bool v) { return value() && dom_.boolean(v); }
  bool number_integer(number_integer_t v) { return value() && dom_.number_integer(v); }
  bool number_unsigned(number_unsigned_t v) { return value() && dom_.number_unsigned(v); }
  bool number_float(number_float_t v, const string_t& s) { return value() && dom_.number_float(v, s); }
  bool string(string_t& v) { return value() && dom_.string(v); }
  bool binary(binary_t& v) { return value() && dom_.binary(v); }
  bool start_object(std::size_t n) { return open(n) && dom_.start_object(n); }
  bool key(string_t& k) { return dom_.key(k); }
  bool end_object() {
    --depth_;
    return dom_.end_object();
  }
  bool start_array(std::size_t n) { return open(n) && dom_.start_array(n); }
  bool end_array() {
    --depth_;
    return dom_.end_array();
  }
  template <class Exception>
  bool parse_error(std::size_t position, const std::string& token, const Exception& ex) {
    return dom_.parse_error(position, token, ex);
  }

  // Stopped by a bound (out_of_range) rather than by bad syntax (garbage).
  bool over_bound() const { return over_bound_; }

 private:
  bool value() {
    if (++values_ <= kMaxPayloadValues) return true;
    over_bound_ = true;
    return false;
  }
  bool open(std::size_t declared) {
    if (!value()) return false;
    const bool unknown = declared == static_cast<std::size_t>(-1);  // JSON text does not say
    if (++depth_ > kMaxNestingDepth || (!unknown && declared > bytes_)) {
      over_bound_ = true;
      return false;
    }
    return true;
  }

  nlohmann::detail::json_sax_dom_parser<json> dom_;
  std::size_t bytes_;
  std::size_t depth_ = 0;
  std::size_t values_ = 0;
  bool over_bound_ = false;
};

// The old path, kept for the benchmarks (old against new in one run): every message
// through an nlohmann tree.
Decoded<std::vector<Message>> decode_payload_tree(Encoding encoding, std::span<const std::uint8_t> payload) {
  if (payload.empty()) return Reject::truncated;
  json j;
  BoundedSax sax(j, payload.size());
  const auto format = encoding == Encoding::json ? json::input_format_t::json : json::input_format_t::msgpack;
  bool parsed = false;
  try {
    parsed = json::sax_parse(payload.begin(), payload.end(), &sax, format, /*strict=*/true);
  } catch (const json::exception&) {
    parsed = false;  // the tree builder refuses sizes beyond max_size() by throwing
  }
  if (sax.over_bound()) return Reject::out_of_range;
  if (!parsed || !j.is_array() || j.empty()) return Reject::garbage;
  if (j.size() > kMaxMessagesPerDatagram) return Reject::out_of_range;
  std::vector<Message> messages;
  messages.reserve(j.size());
  try {
    for (const auto& item : j) messages.push_back(message_from_json(item));
  } catch (const detail::DecodeFail& e) {
    return e.reason;
  } catch (const json::exception&) {
    return Reject::garbage;
  }
  return messages;
}

// Messages that have a field table are written by it; the others (converted last) still
// go through their nlohmann mapping, spliced in as already-encoded bytes.
void put_legacy(wire::MsgpackWriter& w, const Message& m) { w.raw(json::to_msgpack(message_to_json(m))); }
void put_legacy(wire::MsgpackCounter& w, const Message& m) { w.raw(json::to_msgpack(message_to_json(m))); }
void put_legacy(wire::JsonWriter& w, const Message& m) { w.raw(dump(message_to_json(m))); }

template <class W>
void write_message(W& w, const Message& m) {
  if (const auto* snap = std::get_if<SnapshotMsg>(&m)) return wire::write_map(w, "snap", *snap, wire::kSnapFields);
  if (const auto* input = std::get_if<Input>(&m)) return wire::write_map(w, "input", *input, wire::kInputFields);
  put_legacy(w, m);
}

template <class W>
void write_messages(W& w, const std::vector<Message>& messages) {
  w.array(messages.size());
  for (const auto& m : messages) write_message(w, m);
}

template <class M, class Table>
Decoded<Message> read_table(wire::MsgpackReader& r, const Table& table) {
  M m;
  wire::read_map(r, m, table);
  wire::check(r, m);
  if (r.failed()) return r.reason();
  return Message{std::move(m)};
}

// One message (a map) at the reader's position: its "t" first, then the table of that
// type reads it from the start.
Decoded<Message> read_message(wire::MsgpackReader& r) {
  const std::size_t start = r.pos();
  const std::size_t n = r.map(kMaxPayloadValues);
  std::string_view type;
  bool typed = false;
  // Our writers put "t" first: then the type is known without a pass over the rest.
  if (n > 0 && r.str(kMaxTextBytes) == "t" && !r.failed()) {
    type = r.str(kMaxTextBytes);
    if (!r.failed() && (type == "snap" || type == "input")) {
      r.seek(start);
      Decoded<Message> out = type == "snap" ? read_table<SnapshotMsg>(r, wire::kSnapFields)
                                            : read_table<Input>(r, wire::kInputFields);
      return out;
    }
  }
  if (r.failed()) return Reject::garbage;
  r.seek(start);
  r.map(kMaxPayloadValues);
  for (std::size_t i = 0; i < n && !r.failed(); ++i) {
    const std::string_view key = r.str(kMaxTextBytes);
    if (key == "t" && !r.failed()) {
      type = r.str(kMaxTextBytes);
      typed = !r.failed();
    } else {
      r.skip();
    }
  }
  if (r.failed() || !typed) return Reject::garbage;
  const std::size_t end = r.pos();
  r.seek(start);
  Decoded<Message> out = Reject::unknown_type;
  if (type == "snap") out = read_table<SnapshotMsg>(r, wire::kSnapFields);
  else if (type == "input") out = read_table<Input>(r, wire::kInputFields);
  else {
    try {
      out = message_from_json(json::from_msgpack(r.bytes(start, end)));
    } catch (const detail::DecodeFail& e) {
      out = e.reason;
    } catch (const json::exception&) {
      out = Reject::garbage;
    }
  }
  r.seek(end);
  return out;
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

// JSON text: nlohmann's bounded parser, then the same table readers over its MessagePack.
Decoded<std::vector<Message>> decode_json(std::span<const std::uint8_t> payload) {
  if (payload.empty()) return Reject::truncated;
  json j;
  BoundedSax sax(j, payload.size());
  bool parsed = false;
  try {
    parsed = json::sax_parse(payload.begin(), payload.end(), &sax, json::input_format_t::json, /*strict=*/true);
  } catch (const json::exception&) {
    parsed = false;
  }
  if (sax.over_bound()) return Reject::out_of_range;
  if (!parsed || !j.is_array() || j.empty()) return Reject::garbage;
  if (j.size() > kMaxMessagesPerDatagram) return Reject::out_of_range;
  return decode_msgpack(json::to_msgpack(j));
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

void append_payload(Encoding encoding, const std::vector<Message>& messages, std::vector<std::uint8_t>& out) {
  if (encoding == Encoding::msgpack) {
    wire::MsgpackWriter w(out);
    write_messages(w, messages);
    return;
  }
  std::string text;
  wire::JsonWriter w(text);
  write_messages(w, messages);
  out.insert(out.end(), text.begin(), text.end());
}

std::size_t payload_bytes(Encoding encoding, const std::vector<Message>& messages) {
  if (encoding == Encoding::msgpack) {
    wire::MsgpackCounter c;
    write_messages(c, messages);
    return c.bytes;
  }
  return to_json_text(messages).size();
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

namespace legacy {
std::vector<std::uint8_t> encode_payload(Encoding encoding, const std::vector<Message>& messages) {
  const json j = messages_to_json(messages);
  if (encoding == Encoding::msgpack) return json::to_msgpack(j);
  const std::string text = dump(j);
  return {text.begin(), text.end()};
}
Decoded<std::vector<Message>> decode_payload(Encoding encoding, std::span<const std::uint8_t> payload) {
  return decode_payload_tree(encoding, payload);
}
}  // namespace legacy

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
