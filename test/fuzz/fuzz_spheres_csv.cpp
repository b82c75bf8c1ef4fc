// libFuzzer target: the spheres CSV of `collide spheres` (world mode), in each link format.
#include <sstream>
#include <string>

#include "cli/spheres_csv.hpp"
#include "csv_format.hpp"
#include "fuzz_input.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto format = collide::fuzz::pickFormat(data, size);
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  collide::SphereTable spheres;
  try {
    collide::cli::readSpheresCsv(in, collide::fuzz::kInputName, format, spheres);
  } catch (const collide::cli::CsvError& e) {
    collide::fuzz::requireNamed("CsvError", e.what());
  }
  return 0;
}
