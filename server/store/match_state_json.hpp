// A whole MatchState as JSON (a journal's checkpoint) and back. Doubles are written in
// nlohmann's shortest round-trip form, so the state read back is bit-identical; the
// caller checks that with match_hash against the hash stored beside the checkpoint.
// The config is not written: a checkpoint is read over make_match(config, seed) of the
// journal's header, which also gives the fields derived from the config (arena, physics).
#pragma once

#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "fts/sim/match.hpp"

namespace fts::store {

nlohmann::json match_state_to_json(const sim::MatchState& state);
// `base` is make_match(config, seed); every dynamic field is replaced by the JSON's.
// On a missing or mistyped field: a message naming it, and nothing is returned.
std::variant<sim::MatchState, std::string> match_state_from_json(const nlohmann::json& j, sim::MatchState base);

}  // namespace fts::store
