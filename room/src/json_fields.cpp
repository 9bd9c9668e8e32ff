#include "fts/room/json_fields.hpp"

#include <cmath>

namespace fts::room {

Fields::Fields(const nlohmann::json& obj, std::string path) : obj_(obj), path_(std::move(path)) {
  if (!obj_.is_object()) throw FieldError(path_ + ": must be an object, got " + obj_.dump());
}

std::string Fields::path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

void Fields::fail(std::string_view key, const std::string& message) const {
  throw FieldError(path(key) + ": " + message);
}

void Fields::only(std::initializer_list<std::string_view> known) const {
  for (const auto& [key, value] : obj_.items()) {
    bool ok = false;
    for (auto k : known) ok = ok || k == key;
    if (!ok) fail(key, "unknown key (value " + value.dump() + ")");
  }
}

const nlohmann::json& Fields::at(std::string_view key) const {
  auto it = obj_.find(key);
  if (it == obj_.end()) fail(key, "missing");
  return *it;
}

double Fields::number(std::string_view key) const {
  const auto& v = at(key);
  if (!v.is_number()) fail(key, "must be a number, got " + v.dump());
  const double d = v.get<double>();
  if (!std::isfinite(d)) fail(key, "must be finite, got " + v.dump());
  return d;
}

double Fields::number_or(std::string_view key, double fallback) const {
  return has(key) ? number(key) : fallback;
}

std::int64_t Fields::integer(std::string_view key) const {
  const auto& v = at(key);
  if (!v.is_number_integer()) fail(key, "must be an integer, got " + v.dump());
  if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX))
    fail(key, "too large, got " + v.dump());
  return v.get<std::int64_t>();
}

std::int64_t Fields::integer_or(std::string_view key, std::int64_t fallback) const {
  return has(key) ? integer(key) : fallback;
}

bool Fields::boolean_or(std::string_view key, bool fallback) const {
  if (!has(key)) return fallback;
  const auto& v = at(key);
  if (!v.is_boolean()) fail(key, "must be true or false, got " + v.dump());
  return v.get<bool>();
}

std::string Fields::string(std::string_view key) const {
  const auto& v = at(key);
  if (!v.is_string()) fail(key, "must be a string, got " + v.dump());
  return v.get<std::string>();
}

std::string Fields::string_or(std::string_view key, std::string fallback) const {
  return has(key) ? string(key) : fallback;
}

void require_positive(const Fields& f, std::string_view key, double v) {
  if (!(v > 0.0)) f.fail(key, "must be > 0, got " + nlohmann::json(v).dump());
}

}  // namespace fts::room
