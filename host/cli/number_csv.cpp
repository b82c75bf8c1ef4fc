#include "cli/number_csv.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "util/echo.hpp"

namespace collide::cli {

namespace {

constexpr std::size_t kMaxLineBytes = 1 << 16;  // a row of 8 hex floats is about 200

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::size_t start = 0;
  for (;;) {
    const auto comma = s.find(',', start);
    out.push_back(trim(s.substr(start, comma - start)));
    if (comma == std::string::npos) return out;
    start = comma + 1;
  }
}

// One field as a value of `format`; false with `why` set if it is not a whole number, or if
// a finite literal overflows and that is an error. `unfit`: the value did not fit (a finite
// literal became infinite, or a non-zero one became zero).
bool parseField(const std::string& f, LinkFormat format, Overflow overflow, double& v, bool& unfit, std::string& why) {
  unfit = false;
  if (f.empty()) { why = "empty field"; return false; }
  if (!format::parseInto(f.c_str(), numberFormat(format), v)) { why = "not a number: '" + util::clip(f) + "'"; return false; }
  const bool literalInf = f.find_first_of("iI") != std::string::npos;
  if (std::isinf(v) && !literalInf) {
    if (overflow == Overflow::Error) {
      why = "'" + util::clip(f) + "' overflows " + toString(format);
      return false;
    }
    unfit = true;
  }
  // A non-zero literal that rounded to zero (long double reaches far below every format's
  // smallest subnormal, so strtold tells a zero literal from an underflowed one).
  if (v == 0 && std::strtold(f.c_str(), nullptr) != 0) unfit = true;
  return true;
}

// std::getline, but a line longer than kMaxLineBytes is an error, not a string of any size
// (a 2 GB file without a newline cost about 5x its size in memory). False at the end.
bool readLine(std::istream& in, std::string& line, const std::function<void(const std::string&)>& tooLong) {
  line.clear();
  std::streambuf* sb = in.rdbuf();
  bool any = false;
  for (;;) {
    const int c = sb->sbumpc();
    if (c == std::char_traits<char>::eof()) {
      in.setstate(std::ios::eofbit);
      return any;
    }
    any = true;
    if (c == '\n') return true;
    if (line.size() >= kMaxLineBytes) tooLong(util::clip(line));
    line.push_back(static_cast<char>(c));
  }
}

}  // namespace

void readNumberCsv(std::istream& in, const std::string& name, LinkFormat format,
                   const std::vector<std::string>& columns,
                   const std::function<void(const double* values, const bool* unfit)>& row, Overflow overflow) {
  auto fail = [&](std::size_t line, const std::string& what) {
    throw CsvError(name + ":" + std::to_string(line) + ": " + what);
  };
  std::string want;
  for (const auto& c : columns) want += (want.empty() ? "" : ",") + c;
  const std::string cols = std::to_string(columns.size());
  std::string raw;
  std::size_t line = 0;
  bool header = false;
  std::vector<double> v(columns.size());
  std::unique_ptr<bool[]> unfit(new bool[columns.size()]);
  while (readLine(in, raw, [&](const std::string& start) {
    fail(line + 1, "line longer than " + std::to_string(kMaxLineBytes) + " bytes (a row is " + cols + " numbers): '" +
                       start + "'");
  })) {
    ++line;
    // A UTF-8 byte-order mark (spreadsheets write one) is not part of the header.
    if (line == 1 && raw.compare(0, 3, "\xEF\xBB\xBF") == 0) raw.erase(0, 3);
    const std::string s = trim(raw);
    if (s.empty()) continue;  // blank lines carry no data
    if (!header) {
      if (s != want) {
        // A header that prints like the expected one differs in bytes one cannot see.
        const bool hidden = std::any_of(s.begin(), s.end(), [](char c) { return static_cast<unsigned char>(c) >= 0x80 || static_cast<unsigned char>(c) < 0x20; });
        fail(line, "expected the header '" + want + "', got '" + util::clip(s) + "'" +
                       (hidden ? " (it holds control or non-ASCII bytes)" : ""));
      }
      header = true;
      continue;
    }
    const auto fields = split(s);
    if (fields.size() != columns.size()) fail(line, "expected " + cols + " fields, got " + std::to_string(fields.size()));
    for (std::size_t k = 0; k < columns.size(); ++k) {
      std::string why;
      if (!parseField(fields[k], format, overflow, v[k], unfit[k], why)) fail(line, columns[k] + ": " + why);
    }
    row(v.data(), unfit.get());
  }
  if (!header) fail(line == 0 ? 1 : line, "empty input: expected the header '" + want + "'");
}

std::string hexFloat(double v, LinkFormat format) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", format::roundTo(v, numberFormat(format)));
  return buf;
}

}  // namespace collide::cli
