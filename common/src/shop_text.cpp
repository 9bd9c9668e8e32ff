#include "fts/sim/shop_text.hpp"

#include <charconv>

namespace fts::sim {

std::string with_thousands(std::int64_t v) {
  const bool neg = v < 0;
  std::uint64_t u = neg ? 0 - static_cast<std::uint64_t>(v) : static_cast<std::uint64_t>(v);
  std::string digits = std::to_string(u);
  std::string out;
  const std::size_t n = digits.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0 && (n - i) % 3 == 0) out += ',';
    out += digits[i];
  }
  return neg ? "-" + out : out;
}

std::string fixed2(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::fixed, 2);
  if (r.ec != std::errc()) return "?";
  return std::string(buf, r.ptr);
}

std::vector<std::string> shop_lines(const Economy& e, std::int64_t level, const ShopTerms& terms) {
  const std::string L = std::to_string(level);
  std::vector<std::string> out = {
      "Level: " + L,
      "Coins: " + with_thousands(e.coins),
      "Lives: " + with_thousands(e.lives),
      "Level " + L + " Complete",
  };
  for (const ItemDef& d : item_table()) {
    out.push_back(d.status(e, terms));
    if (d.owned && d.owned(e)) continue;
    out.push_back(std::string(d.offer) + ", press '" + d.key + "' (" + with_thousands(price_of(e, d.item)) + " coins)");
    if (d.note) out.push_back(d.note(terms));
  }
  out.push_back("Press Enter to begin next level.");
  return out;
}

}  // namespace fts::sim
