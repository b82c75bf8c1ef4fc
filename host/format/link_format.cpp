#include "format/link_format.hpp"

namespace collide {

const char* toString(LinkFormat f) {
  switch (f) {
    case LinkFormat::Binary16: return "binary16";
    case LinkFormat::BFloat16: return "bfloat16";
    case LinkFormat::Binary32: return "binary32";
    case LinkFormat::Binary64: return "binary64";
  }
  return "?";
}

format::NumberFormat numberFormat(LinkFormat f) {
  switch (f) {
    case LinkFormat::Binary16: return format::kBinary16;
    case LinkFormat::BFloat16: return format::kBFloat16;
    case LinkFormat::Binary32: return format::kBinary32;
    case LinkFormat::Binary64: return format::kBinary64;
  }
  return format::kBinary64;
}

bool linkFormatFromString(const std::string& name, LinkFormat& out) {
  for (LinkFormat f : {LinkFormat::Binary16, LinkFormat::BFloat16, LinkFormat::Binary32, LinkFormat::Binary64})
    if (name == toString(f)) { out = f; return true; }
  return false;
}

}  // namespace collide
