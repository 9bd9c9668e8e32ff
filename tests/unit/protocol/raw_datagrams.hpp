// Hand-made datagrams for the decoder's bounds (a header, then any payload bytes),
// shared by test_decode_bounds.cpp and the benchmark of tests/bench/protocol_bench.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fts/protocol/header.hpp"

namespace fts::protocol::test {

inline std::vector<std::uint8_t> raw_datagram(const std::vector<std::uint8_t>& payload, Encoding enc) {
  Header h;
  h.encoding = enc;
  std::vector<std::uint8_t> out;
  write_header(h, out);
  out.insert(out.end(), payload.begin(), payload.end());
  return out;
}

inline std::vector<std::uint8_t> bytes_of(const std::string& s) { return {s.begin(), s.end()}; }

// `depth` JSON arrays, each inside the last.
inline std::vector<std::uint8_t> nested_json(std::size_t depth) {
  return bytes_of(std::string(depth, '[') + std::string(depth, ']'));
}

// MessagePack fixarray of one element, `depth` times, around an empty array.
inline std::vector<std::uint8_t> nested_msgpack(std::size_t depth) {
  std::vector<std::uint8_t> out(depth, 0x91);
  out.push_back(0x90);
  return out;
}

}  // namespace fts::protocol::test
