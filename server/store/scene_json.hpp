// Reading a physics scene from JSON text, with errors that name the field and value.
#pragma once

#include <string>
#include <variant>

#include "fts/sim/scene.hpp"

namespace fts::store {

// Either the scene or a message such as "balls[3].r: must be > 0, got -1".
std::variant<sim::Scene, std::string> parse_scene(const std::string& json_text);

}  // namespace fts::store
