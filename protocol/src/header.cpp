#include "fts/protocol/header.hpp"

namespace fts::protocol {
namespace {

void put16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v >> 8));
  out.push_back(static_cast<std::uint8_t>(v));
}
void put32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  put16(out, static_cast<std::uint16_t>(v >> 16));
  put16(out, static_cast<std::uint16_t>(v));
}
std::uint16_t get16(std::span<const std::uint8_t> b, std::size_t at) {
  return static_cast<std::uint16_t>((b[at] << 8) | b[at + 1]);
}
std::uint32_t get32(std::span<const std::uint8_t> b, std::size_t at) {
  return (std::uint32_t{get16(b, at)} << 16) | get16(b, at + 2);
}

}  // namespace

void write_header_prefix(const Header& header, std::vector<std::uint8_t>& out) {
  put32(out, kProtocolId);
  put16(out, header.version);
  out.push_back(static_cast<std::uint8_t>(header.encoding));
  put32(out, header.session);
  put16(out, header.sequence);
  put16(out, header.ack);
  put32(out, header.ack_bits);
}

void write_header(const Header& header, std::vector<std::uint8_t>& out) {
  write_header_prefix(header, out);
  put16(out, header.ack_delay_ms);
}

Decoded<Header> read_header_any_version(std::span<const std::uint8_t> bytes) {
  if (bytes.size() > kMaxDatagramBytes) return Reject::oversize;
  if (bytes.size() < kHeaderPrefixBytes) return Reject::truncated;
  if (get32(bytes, 0) != kProtocolId) return Reject::wrong_protocol_id;
  Header h;
  h.version = get16(bytes, 4);
  const std::uint8_t flags = bytes[6];
  if (flags > 1) return Reject::bad_flags;
  h.encoding = static_cast<Encoding>(flags);
  h.session = get32(bytes, 7);
  h.sequence = get16(bytes, 11);
  h.ack = get16(bytes, 13);
  h.ack_bits = get32(bytes, 15);
  return h;
}

Decoded<Header> read_header(std::span<const std::uint8_t> bytes, std::uint16_t expected_version) {
  auto h = read_header_any_version(bytes);
  if (!h) return h;
  if (h->version != expected_version) return Reject::bad_version;
  if (bytes.size() < kHeaderBytes) return Reject::truncated;
  h->ack_delay_ms = get16(bytes, kHeaderPrefixBytes);
  return h;
}

}  // namespace fts::protocol
