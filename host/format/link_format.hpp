#pragma once
// The number format of every field on the host<->AFU link (docs/afu-interface.md, "Link
// format"): the manifest's link.format.
#include <string>

#include "format/number_format.hpp"

namespace collide {

enum class LinkFormat { Binary16, BFloat16, Binary32, Binary64 };

const char* toString(LinkFormat f);
format::NumberFormat numberFormat(LinkFormat f);
// From the manifest's name (binary16, bfloat16, binary32, binary64); false if unknown.
bool linkFormatFromString(const std::string& name, LinkFormat& out);
// Bytes of one field.
inline unsigned fieldBytes(LinkFormat f) { return static_cast<unsigned>(numberFormat(f).width()) / 8; }

}  // namespace collide
