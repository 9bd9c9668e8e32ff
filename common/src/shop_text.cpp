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

std::vector<std::string> shop_lines(const Economy& e, std::int64_t level) {
  auto price = [&](Item it) { return "(" + with_thousands(price_of(e, it)) + " coins)"; };
  const std::string L = std::to_string(level);
  std::vector<std::string> out = {
      "Level: " + L,
      "Coins: " + with_thousands(e.coins),
      "Lives: " + with_thousands(e.lives),
      "Level " + L + " Complete",
      "Current Mass: " + with_thousands(e.mass),
      "To increase Mass, press 'm' " + price(Item::mass),
      // Speeds in the original's units: u/frame, and u/frame^2 x 100 (frame 0.01 s).
      "Current Max Speed: " + fixed2(e.vmax_u_per_s / 100.0),
      "To increase Max Speed, press 's' " + price(Item::speed),
      "Current Acceleration: " + fixed2(e.accel_u_per_s2 / 100.0),
      "To increase Acceleration, press 'a' " + price(Item::accel),
      std::string("Current Weapon: ") + (e.rockets ? "ROCKETS." : "NONE."),
  };
  if (!e.rockets) out.push_back("To purchase rockets, press 'r' " + price(Item::rockets));
  out.push_back("Current Lives: " + with_thousands(e.lives));
  out.push_back("To add a life, press 'l' " + price(Item::life));
  out.push_back("Current Multiplier: " + fixed2(e.multiplier));
  out.push_back("To increase multiplier, press 'x' " + price(Item::multiplier));
  out.push_back("Increases coins from enemies by 10%");
  out.push_back(std::string("Bank Purchased: ") + (e.bank ? "True" : "False"));
  if (!e.bank) {
    out.push_back("To purchase bank, press 'b' " + price(Item::bank));
    out.push_back("Earns 10% interest per round");
  }
  out.push_back("Press Enter to begin next level.");
  return out;
}

}  // namespace fts::sim
