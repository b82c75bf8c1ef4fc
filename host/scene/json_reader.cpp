#include "scene/json_reader.hpp"

#include <cmath>
#include <limits>

#include "util/echo.hpp"

namespace collide::scene {

namespace {
// Bounded in length and in the part of j it visits (util/echo.hpp).
std::string shortDump(const nlohmann::json& j) { return util::echoJson(j); }
}  // namespace

void JsonNode::fail(const std::string& what) const { throw SceneError(path_ + ": " + what); }
void JsonNode::expected(const std::string& what) const { fail("expected " + what + ", got " + shortDump(*j_)); }

void JsonNode::requireObject() const {
  if (!j_->is_object()) expected("an object");
}

void JsonNode::allowOnly(std::initializer_list<const char*> keys) const {
  requireObject();
  for (const auto& item : j_->items()) {
    bool known = false;
    for (const char* k : keys) known = known || item.key() == k;
    if (!known) {
      std::string list;
      for (const char* k : keys) list += (list.empty() ? "" : ", ") + std::string(k);
      JsonNode(item.value(), path_ + "." + item.key()).fail("unknown key (known here: " + list + ")");
    }
  }
}

bool JsonNode::has(const char* key) const { return j_->is_object() && j_->contains(key); }

JsonNode JsonNode::at(const char* key) const {
  requireObject();
  if (!j_->contains(key)) JsonNode(*j_, path_ + "." + key).fail("missing");
  return JsonNode(j_->at(key), path_ + "." + key);
}

std::optional<JsonNode> JsonNode::find(const char* key) const {
  if (!has(key)) return std::nullopt;
  return JsonNode(j_->at(key), path_ + "." + key);
}

std::size_t JsonNode::arraySize() const {
  if (!j_->is_array()) expected("an array");
  return j_->size();
}

JsonNode JsonNode::operator[](std::size_t k) const {
  return JsonNode(j_->at(k), path_ + "[" + std::to_string(k) + "]");
}

double JsonNode::number() const {
  if (!j_->is_number() || !std::isfinite(j_->get<double>())) expected("a number");
  return j_->get<double>();
}
double JsonNode::positive() const {
  if (!j_->is_number() || !(j_->get<double>() > 0) || !std::isfinite(j_->get<double>()))
    expected("a positive number");
  return j_->get<double>();
}
double JsonNode::nonNegative() const {
  if (!j_->is_number() || !(j_->get<double>() >= 0) || !std::isfinite(j_->get<double>()))
    expected("a number >= 0");
  return j_->get<double>();
}
double JsonNode::nonNegativeOrInfinity() const {
  if (j_->is_string() && (j_->get<std::string>() == "infinity" || j_->get<std::string>() == "inf"))
    return std::numeric_limits<double>::infinity();
  if (!j_->is_number() || !(j_->get<double>() >= 0)) expected("a number >= 0 or \"infinity\"");
  return j_->get<double>();
}
long long JsonNode::positiveInt() const {
  if (!j_->is_number_integer() || j_->get<long long>() < 1) expected("a positive integer");
  return j_->get<long long>();
}
long long JsonNode::nonNegativeInt() const {
  if (!j_->is_number_integer() || j_->get<long long>() < 0) expected("an integer >= 0");
  return j_->get<long long>();
}
std::uint64_t JsonNode::seed() const {
  if (!j_->is_number_unsigned()) expected("an unsigned integer");
  return j_->get<std::uint64_t>();
}
bool JsonNode::boolean() const {
  if (!j_->is_boolean()) expected("true or false");
  return j_->get<bool>();
}
std::string JsonNode::string() const {
  if (!j_->is_string()) expected("a string");
  return j_->get<std::string>();
}
Vec3 JsonNode::vec3() const {
  if (!j_->is_array() || j_->size() != 3) expected("[x, y, z]");
  Vec3 v;
  for (std::size_t k = 0; k < 3; ++k) v[k] = (*this)[k].number();
  return v;
}

}  // namespace collide::scene
