// Replays fuzz inputs through a target without libFuzzer, so the committed corpora run as
// ordinary ctest cases in any build (GCC included): each argument is a file or a folder of
// files, each file is one input. A refused input is fine; a crash, an abort or an uncaught
// exception fails the test, as it would under the fuzzer.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

void replay(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t n = 0;
  for (int a = 1; a < argc; ++a) {
    const std::filesystem::path arg(argv[a]);
    if (std::filesystem::is_directory(arg)) {
      std::vector<std::filesystem::path> files;
      for (const auto& e : std::filesystem::directory_iterator(arg))
        if (e.is_regular_file()) files.push_back(e.path());
      std::sort(files.begin(), files.end());  // a fixed order, so a failure repeats
      for (const auto& f : files) replay(f), ++n;
    } else if (std::filesystem::is_regular_file(arg)) {
      replay(arg), ++n;
    } else {
      std::fprintf(stderr, "replay: %s: no such file or folder\n", argv[a]);
      return 2;
    }
  }
  if (n == 0) {
    std::fprintf(stderr, "replay: no inputs given (an empty corpus proves nothing)\n");
    return 2;
  }
  std::printf("replay: %zu inputs, none crashed\n", n);
  return 0;
}
