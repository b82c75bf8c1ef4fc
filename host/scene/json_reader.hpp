#pragma once
// Reading JSON with the key path in every error message, e.g.
//   scene.bodies.diamond.hMax: expected a positive integer, got -3
// Objects are checked for unknown keys, so a misspelt effect is an error, not a no-op.
#include <array>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace collide::scene {

struct SceneError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using Vec3 = std::array<double, 3>;

class JsonNode {
 public:
  JsonNode(const nlohmann::json& j, std::string path) : j_(&j), path_(std::move(path)) {}

  const std::string& path() const { return path_; }
  const nlohmann::json& json() const { return *j_; }
  [[noreturn]] void fail(const std::string& what) const;
  [[noreturn]] void expected(const std::string& what) const;  // "expected <what>, got <value>"

  // Objects
  void requireObject() const;
  void allowOnly(std::initializer_list<const char*> keys) const;
  bool has(const char* key) const;
  JsonNode at(const char* key) const;                 // missing -> error
  std::optional<JsonNode> find(const char* key) const;
  // Arrays
  std::size_t arraySize() const;                       // not an array -> error
  JsonNode operator[](std::size_t k) const;

  // Scalars
  double number() const;           // finite
  double positive() const;         // > 0, finite
  double nonNegative() const;      // >= 0, finite
  double nonNegativeOrInfinity() const;  // also "infinity"/"inf" (JSON has no infinity)
  long long positiveInt() const;   // integer >= 1
  long long nonNegativeInt() const;
  std::uint64_t seed() const;      // unsigned integer
  bool boolean() const;
  std::string string() const;
  Vec3 vec3() const;               // [x, y, z] of finite numbers

 private:
  const nlohmann::json* j_;
  std::string path_;
};

}  // namespace collide::scene
