#include "fts/protocol/codec.hpp"

#include "mapping.hpp"

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

Decoded<std::vector<Message>> decode_payload(Encoding encoding, std::span<const std::uint8_t> payload) {
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

}  // namespace

std::vector<std::uint8_t> encode_payload(Encoding encoding, const std::vector<Message>& messages) {
  const json j = messages_to_json(messages);
  if (encoding == Encoding::msgpack) return json::to_msgpack(j);
  const std::string text = dump(j);
  return {text.begin(), text.end()};
}

std::string to_json_text(const std::vector<Message>& messages) { return dump(messages_to_json(messages)); }

std::vector<std::uint8_t> encode_datagram(const Header& header, const std::vector<Message>& messages) {
  std::vector<std::uint8_t> out;
  out.reserve(256);
  write_header(header, out);
  const auto payload = encode_payload(header.encoding, messages);
  out.insert(out.end(), payload.begin(), payload.end());
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
