#pragma once
// What an error message may quote of an offending input: at most kEchoChars characters,
// then "...". A 50 MB garbage line or a deeply nested JSON value is shown by its start
// and its size, never echoed whole (nor walked whole: echoJson stops at the limit).
#include <cstddef>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace collide::util {

constexpr std::size_t kEchoChars = 80;

// `s` itself if short enough, else its first `max` characters (not splitting a UTF-8
// sequence) + "... (N bytes)".
std::string clip(std::string_view s, std::size_t max = kEchoChars);

// j as compact JSON, clipped like clip(); visits only what it prints, so its cost and its
// recursion are bounded by `max` whatever the size or depth of j.
std::string echoJson(const nlohmann::json& j, std::size_t max = kEchoChars);

}  // namespace collide::util
