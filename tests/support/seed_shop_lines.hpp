// The seed's shop slide, line for line (../shared/seed): level 3 complete, 286 coins,
// 1 life, multiplier 1.06, no bank. Both the match's shop text and the client's shop
// screen must reproduce it.
#pragma once

#include <string>
#include <vector>

namespace fts::test {

inline const std::vector<std::string>& seed_shop_lines() {
  static const std::vector<std::string> lines = {
      "Level: 3",
      "Coins: 286",
      "Lives: 1",
      "Level 3 Complete",
      "Current Mass: 40",
      "To increase Mass, press 'm' (35 coins)",
      "Current Max Speed: 1.70",
      "To increase Max Speed, press 's' (100 coins)",
      "Current Acceleration: 2.00",
      "To increase Acceleration, press 'a' (150 coins)",
      "Current Weapon: NONE.",
      "To purchase rockets, press 'r' (1,000,000 coins)",
      "Current Lives: 1",
      "To add a life, press 'l' (522 coins)",
      "Current Multiplier: 1.06",
      "To increase multiplier, press 'x' (100 coins)",
      "Increases coins from enemies by 10%",
      "Bank Purchased: False",
      "To purchase bank, press 'b' (500 coins)",
      "Earns 10% interest per round",
      "Press Enter to begin next level.",
  };
  return lines;
}

}  // namespace fts::test
