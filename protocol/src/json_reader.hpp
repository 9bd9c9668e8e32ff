// JSON text in, MessagePack out (internal): the JSON reader of the codec. nlohmann's SAX
// parser drives a writer straight into MessagePack bytes (no tree), behind the payload
// bounds of PROTOCOL.md 10; the field tables then read those bytes like any MessagePack
// payload, so there is one reader per message for both encodings.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "fts/protocol/reject.hpp"

namespace fts::protocol::wire {

// Appends the MessagePack form of the JSON `text` to `out`. Returns false with `why`
// (garbage: not JSON, or a byte order mark first; out_of_range: nested deeper than kMaxNestingDepth or more than
// kMaxPayloadValues values) and then `out` holds a partial value.
bool json_to_msgpack(std::span<const std::uint8_t> text, std::vector<std::uint8_t>& out, Reject& why);

}  // namespace fts::protocol::wire
