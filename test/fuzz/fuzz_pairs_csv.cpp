// libFuzzer target: the pairs CSV of `collide pairs` (vector mode), in each link format.
#include <sstream>
#include <string>
#include <vector>

#include "cli/pairs_csv.hpp"
#include "csv_format.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto format = collide::fuzz::pickFormat(data, size);
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  collide::SphereTable spheres;
  collide::PairList pairs;
  std::vector<std::uint8_t> didNotFit;
  try {
    collide::cli::readPairsCsv(in, collide::fuzz::kInputName, format, spheres, pairs, didNotFit);
    // Every pair row becomes two spheres, each with its didNotFit entry.
    if (spheres.size() != 2 * pairs.size() || didNotFit.size() != spheres.size()) std::abort();
  } catch (const collide::cli::CsvError& e) {
    collide::fuzz::requireNamed("CsvError", e.what());
  }
  return 0;
}
