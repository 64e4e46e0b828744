// Runs the fuzz target's checks (fuzz_pw85.cpp, fuzz_scene.cpp) over the
// files of a corpus without libFuzzer, so that every build of the suite
// runs them on the code it has: GCC's x86-64-v3 and x86-64-v4 variants
// (which the Clang build of .ci/fuzz does not have), the portable build and
// the sanitized builds, and the x86-64-v3 path under valgrind. A violated
// promise stops the program (__builtin_trap). Prints the digest of every
// status and verdict met (fuzz_checks.hpp, record()); .ci/run compares the
// digests of the builds and variants, which must be equal.
//
// usage: fuzz-replay [--trace] CORPUS_DIR_OR_FILE...
//   --trace: also print each input's name and every status recorded.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "fuzz_checks.hpp"

extern "C" int LLVMFuzzerInitialize(int *, char ***);
extern "C" int LLVMFuzzerTestOneInput(std::uint8_t const *data, std::size_t size);

int main(int argc, char **argv) {
  std::vector<std::string> files;
  for (int a = 1; a < argc; ++a) {
    if (std::strcmp(argv[a], "--trace") == 0) {
      fuzz::trace = stdout;
      continue;
    }
    std::filesystem::path const p(argv[a]);
    if (std::filesystem::is_directory(p)) {
      for (auto const &e : std::filesystem::directory_iterator(p))
        if (e.is_regular_file()) files.push_back(e.path().string());
    } else {
      files.push_back(p.string());
    }
  }
  // Sorted by name: the digest depends on the order.
  std::sort(files.begin(), files.end(), [](std::string const &a, std::string const &b) {
    return std::filesystem::path(a).filename() < std::filesystem::path(b).filename();
  });
  if (files.empty()) {
    std::fprintf(stderr, "fuzz-replay: no input files\n");
    return 1;
  }
  LLVMFuzzerInitialize(&argc, &argv);
  for (auto const &f : files) {
    std::ifstream in(f, std::ios::binary);
    std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (fuzz::trace) std::fprintf(fuzz::trace, "== %s\n", std::filesystem::path(f).filename().c_str());
    LLVMFuzzerTestOneInput(reinterpret_cast<std::uint8_t const *>(data.data()), data.size());
  }
  std::printf("%zu inputs\nfuzz-replay digest %016llx\n", files.size(),
              static_cast<unsigned long long>(fuzz::digest()));
  return 0;
}
