// PROTOCOL.md and the code's tables of codes (codes.hpp, reject.hpp) are one contract:
// 4.4's error codes, 4.7's result codes and section 11's drop reasons are each one
// markdown table, and every row of it is a row of the code's table with the same
// meaning, and the other way round. A code named anywhere in the document's prose
// (`error{code:"..."}`) is one of the table's.
#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "fts/protocol/codes.hpp"
#include "fts/protocol/reject.hpp"

using namespace fts::protocol;

namespace {

std::string document() {
  std::ifstream in(std::string(FTS_SOURCE_DIR) + "/protocol/PROTOCOL.md");
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::string trim(std::string s) {
  const auto a = s.find_first_not_of(" \t");
  const auto b = s.find_last_not_of(" \t");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// The cells of a markdown table row ("| a | b |" -> {"a", "b"}).
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  for (std::size_t i = 1; i < line.size(); ++i) {
    if (line[i] == '|') {
      out.push_back(trim(cell));
      cell.clear();
    } else {
      cell += line[i];
    }
  }
  return out;
}

// The first table after the heading that starts with `heading` whose first column is
// `column`: {name (without its backticks): meaning}. Duplicated names are returned in `twice`.
std::map<std::string, std::string> table_after(const std::string& doc, const std::string& heading,
                                               const std::string& column, std::vector<std::string>& twice) {
  std::map<std::string, std::string> rows;
  std::istringstream in(doc);
  std::string line;
  bool in_section = false, in_table = false;
  while (std::getline(in, line)) {
    if (!in_section) {
      in_section = line.rfind(heading, 0) == 0;
      continue;
    }
    if (!in_table) {
      if (line.rfind("#", 0) == 0) break;  // the next section: no such table
      in_table = line.rfind("|", 0) == 0 && !cells(line).empty() && cells(line)[0] == column;
      continue;
    }
    if (line.rfind("|", 0) != 0) break;
    const auto c = cells(line);
    if (c.size() < 2 || c[0].find_first_not_of("-: ") == std::string::npos) continue;  // the rule row
    std::string name = c[0];
    if (name.size() >= 2 && name.front() == '`' && name.back() == '`') name = name.substr(1, name.size() - 2);
    if (rows.count(name)) twice.push_back(name);
    rows[name] = c[1];
  }
  return rows;
}

template <class E, std::size_t N>
void check_table(const std::array<CodeRow<E>, N>& code, const std::string& heading, const std::string& column) {
  std::vector<std::string> twice;
  const auto doc = table_after(document(), heading, column, twice);
  INFO("PROTOCOL.md " << heading);
  REQUIRE_FALSE(doc.empty());
  CHECK(twice.empty());
  for (const auto& row : code) {
    if (!row.sent) continue;
    INFO("code " << row.name);
    const auto it = doc.find(std::string(row.name));
    CHECK(it != doc.end());  // missing from the document
    if (it != doc.end()) CHECK(it->second == row.meaning);
  }
  for (const auto& [name, meaning] : doc) {
    INFO("document row " << name << ": " << meaning);
    const auto c = code_in(code, name);
    CHECK((c && code[static_cast<std::size_t>(*c)].sent));  // not in the code's table
  }
}

}  // namespace

TEST_CASE("Codes: 4.4's error codes are kErrorCodes", "[protocol][codes]") {
  check_table(kErrorCodes, "### 4.4 ", "code");
}

TEST_CASE("Codes: 4.7's result codes are kResultCodes", "[protocol][codes]") {
  check_table(kResultCodes, "### 4.7 ", "code");
}

TEST_CASE("Codes: section 11's drop reasons are kRejects", "[protocol][codes]") {
  check_table(kRejects, "## 11. ", "reason");
}

TEST_CASE("Codes: every error{code:...} the document names is in the table", "[protocol][codes]") {
  const std::string doc = document();
  const auto names_after = [&](const std::string& prefix) {
    std::vector<std::string> out;
    for (auto at = doc.find(prefix); at != std::string::npos; at = doc.find(prefix, at + 1)) {
      const auto from = at + prefix.size();
      out.push_back(doc.substr(from, doc.find('"', from) - from));
    }
    return out;
  };
  const auto errors = names_after("error{code:\"");
  CHECK(errors.size() >= 10);
  for (const auto& name : errors) {
    INFO("error{code:\"" << name << "\"}");
    const auto c = error_code_of(name);
    CHECK((c && kErrorCodes[static_cast<std::size_t>(*c)].sent));
  }
  for (const auto& name : names_after("code:\"")) {  // results' too: every code in prose is a code
    INFO("code:\"" << name << "\"");
    CHECK((error_code_of(name) || result_code_of(name)));
  }
}

TEST_CASE("Codes: names and enums map both ways", "[protocol][codes]") {
  for (const auto& r : kErrorCodes) CHECK(error_code_of(to_string(r.code)) == r.code);
  for (const auto& r : kResultCodes) CHECK(result_code_of(to_string(r.code)) == r.code);
  for (const auto& r : kRejects) CHECK(code_in(kRejects, to_string(r.code)) == r.code);
  CHECK_FALSE(error_code_of("full"));
  CHECK(has_code(make_error(ErrorCode::server_full, "x"), ErrorCode::server_full));
}
