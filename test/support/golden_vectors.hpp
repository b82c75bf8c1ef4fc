#pragma once
// Golden vectors from the Scala golden model (test/vectors/*.csv, provided by the lead).
//
// Format (docs/host.md, "Golden vectors"): a header row naming the columns, then one pair a
// row. Columns are found by name, in any order; other columns are ignored:
//   inputs   x1,y1,z1,r1,x2,y2,z2,r2             (decimal or C99 hex floats)
//   expected hit,px,py,pz,nx,ny,nz,depth          (hit 0/1; the values in the link format,
//            optionally prefixed exp_ / expected_  hex floats preferred; a miss may be zeros)
//            flags                                (optional: the dense record's flags byte)
//            d,w                                  (optional: the derived record's values)
// Inputs are parsed straight into the link format (one rounding), like `collide pairs`.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "batch/batch.hpp"
#include "format/number_format.hpp"

namespace collide::test {

struct GoldenRow {
  std::size_t line = 0;
  bool hit = false;
  double v[7] = {};                  // px, py, pz, nx, ny, nz, depth
  std::optional<unsigned> flags;
  std::optional<double> d, w;        // the derived record's values, where the file has them
};

struct GoldenVectors {
  SphereTable spheres;  // pair k: spheres 2k and 2k+1
  PairList pairs;
  std::vector<GoldenRow> expected;
};

inline GoldenVectors readGoldenVectors(const std::string& file, LinkFormat format) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file + ": cannot open");
  auto trim = [](std::string s) {
    const auto b = s.find_first_not_of(" \t\r");
    if (b == std::string::npos) return std::string();
    return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
  };
  auto split = [&](const std::string& s) {
    std::vector<std::string> out;
    std::stringstream ss(s);
    std::string f;
    while (std::getline(ss, f, ',')) out.push_back(trim(f));
    if (!s.empty() && s.back() == ',') out.push_back("");
    return out;
  };
  GoldenVectors g;
  std::map<std::string, std::size_t> col;
  std::string raw;
  std::size_t line = 0;
  auto fail = [&](const std::string& what) { throw std::runtime_error(file + ":" + std::to_string(line) + ": " + what); };
  auto find = [&](const std::string& name, bool required) -> std::optional<std::size_t> {
    for (const char* prefix : {"", "exp_", "expected_"}) {
      auto it = col.find(prefix + name);
      if (it != col.end()) return it->second;
    }
    if (required) fail("no column '" + name + "' in the header");
    return std::nullopt;
  };
  static const char* in8[8] = {"x1", "y1", "z1", "r1", "x2", "y2", "z2", "r2"};
  static const char* out7[7] = {"px", "py", "pz", "nx", "ny", "nz", "depth"};
  std::size_t ci[8], co[7], chit = 0;
  std::optional<std::size_t> cflags, cd, cw;
  bool header = false;
  const format::NumberFormat nf = numberFormat(format);
  auto number = [&](const std::string& f, bool inLinkFormat, const char* what) {
    double v = 0;
    if (f.empty() || !format::parseInto(f.c_str(), inLinkFormat ? nf : format::kBinary64, v))
      fail(std::string(what) + ": not a number: '" + f + "'");
    return v;
  };
  auto linkValue = [&](const std::string& f, const char* what) {
    const double v = number(f, false, what);
    if (!format::representable(v, nf)) fail(std::string(what) + ": '" + f + "' is not a " + toString(format) + " value");
    return v;
  };
  while (std::getline(in, raw)) {
    ++line;
    const std::string s = trim(raw);
    if (s.empty() || s[0] == '#') continue;
    const auto fields = split(s);
    if (!header) {
      for (std::size_t k = 0; k < fields.size(); ++k) col[fields[k]] = k;
      for (int k = 0; k < 8; ++k) ci[k] = *find(in8[k], true);
      for (int k = 0; k < 7; ++k) co[k] = *find(out7[k], true);
      chit = *find("hit", true);
      cflags = find("flags", false);
      cd = find("d", false);
      cw = find("w", false);
      header = true;
      continue;
    }
    if (fields.size() < col.size()) fail("expected " + std::to_string(col.size()) + " fields, got " + std::to_string(fields.size()));
    double x[8];
    for (int k = 0; k < 8; ++k) x[k] = number(fields[ci[k]], true, in8[k]);
    const auto a = static_cast<std::uint32_t>(g.spheres.size());
    g.spheres.push(x[0], x[1], x[2], x[3]);
    g.spheres.push(x[4], x[5], x[6], x[7]);
    g.pairs.push(a, a + 1);
    GoldenRow r;
    r.line = line;
    r.hit = number(fields[chit], false, "hit") != 0;
    for (int k = 0; k < 7; ++k) r.v[k] = linkValue(fields[co[k]], out7[k]);
    if (cflags) r.flags = static_cast<unsigned>(std::stoul(fields[*cflags], nullptr, 0));
    if (cd) r.d = linkValue(fields[*cd], "d");
    if (cw) r.w = linkValue(fields[*cw], "w");
    g.expected.push_back(r);
  }
  if (!header) throw std::runtime_error(file + ": empty (no header)");
  return g;
}

}  // namespace collide::test
