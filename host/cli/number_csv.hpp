#pragma once
// Reading a CSV of numbers with a fixed header (`collide pairs`, `collide spheres`): decimal
// or C99 hex floats parsed straight into a link format with one correct rounding
// (format::parseInto); a finite literal that overflows the format is an error. Blank lines
// are skipped, a UTF-8 byte-order mark before the header is accepted, a line longer than
// 64 KiB is an error (a file without newlines costs no more memory than that).
#include <functional>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "format/link_format.hpp"

namespace collide::cli {

struct CsvError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Calls row(values, unfit) for each data row, values[k] the column columns[k] (the header is
// the columns joined by commas). With Overflow::Error a finite literal that overflows the
// format is an error; with Overflow::Flag it becomes the infinity the rounding gives and
// unfit[k] is set, as it is for a non-zero literal that became zero (unfit is all false
// otherwise). Throws CsvError "<name>:<line>: <what>".
enum class Overflow { Error, Flag };
void readNumberCsv(std::istream& in, const std::string& name, LinkFormat format,
                   const std::vector<std::string>& columns,
                   const std::function<void(const double* values, const bool* unfit)>& row,
                   Overflow overflow = Overflow::Error);

// %a of v, printed as a value of `format` (v must be exact in it).
std::string hexFloat(double v, LinkFormat format);

}  // namespace collide::cli
