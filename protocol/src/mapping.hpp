// The nlohmann-json mapping of every message (internal). One mapping per message; the
// codec turns the resulting json value into JSON text or MessagePack.
#pragma once

#include <nlohmann/json.hpp>

#include "fts/protocol/messages.hpp"
#include "json_util.hpp"

namespace fts::protocol {

void to_json(nlohmann::json& j, const Hello& m);
void to_json(nlohmann::json& j, const Challenge& m);
void to_json(nlohmann::json& j, const Welcome& m);
void to_json(nlohmann::json& j, const Error& m);
void to_json(nlohmann::json& j, const Input& m);
void to_json(nlohmann::json& j, const Command& m);
void to_json(nlohmann::json& j, const Result& m);
void to_json(nlohmann::json& j, const Ping& m);
void to_json(nlohmann::json& j, const Bye& m);
void to_json(nlohmann::json& j, const SnapshotMsg& m);

void from_json(const nlohmann::json& j, Hello& m);
void from_json(const nlohmann::json& j, Challenge& m);
void from_json(const nlohmann::json& j, Welcome& m);
void from_json(const nlohmann::json& j, Error& m);
void from_json(const nlohmann::json& j, Input& m);
void from_json(const nlohmann::json& j, Command& m);
void from_json(const nlohmann::json& j, Result& m);
void from_json(const nlohmann::json& j, Ping& m);
void from_json(const nlohmann::json& j, Bye& m);
void from_json(const nlohmann::json& j, SnapshotMsg& m);

// {"t": type, ...fields}
nlohmann::json message_to_json(const Message& m);
// Throws detail::DecodeFail (unknown_type, garbage, out_of_range).
Message message_from_json(const nlohmann::json& j);

}  // namespace fts::protocol
