// The shop screen as text lines, in the seed's wording, e.g.
// "To add a life, press 'l' (522 coins)". The client prints these; tests check them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fts/sim/economy.hpp"

namespace fts::sim {

// 1000000 -> "1,000,000" (negative values keep their sign).
std::string with_thousands(std::int64_t v);
// Two decimals, locale-free and correctly rounded: 1.0612 -> "1.06".
std::string fixed2(double v);

// The shop after `level` was completed, for a player's economy: four heading lines, then
// each item's lines (item table order), then the prompt. `terms` are the server's.
std::vector<std::string> shop_lines(const Economy& e, std::int64_t level, const ShopTerms& terms = {});

}  // namespace fts::sim
