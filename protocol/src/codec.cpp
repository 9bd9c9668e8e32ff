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

Decoded<std::vector<Message>> decode_payload(Encoding encoding, std::span<const std::uint8_t> payload) {
  if (payload.empty()) return Reject::truncated;
  json j;
  if (encoding == Encoding::json) {
    j = json::parse(payload.begin(), payload.end(), nullptr, /*allow_exceptions=*/false);
  } else {
    j = json::from_msgpack(payload.begin(), payload.end(), /*strict=*/true, /*allow_exceptions=*/false);
  }
  if (j.is_discarded() || !j.is_array() || j.empty()) return Reject::garbage;
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
