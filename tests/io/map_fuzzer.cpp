// libFuzzer target for the map readers (ROS YAML, PGM, PNG: readGridMap), beside carmen_fuzzer.cpp: every input
// must give a map or an InputError naming the file on one line (tests/io/map_fuzz_common.h). Build (clang only):
//   cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
//         -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined" -DGRIDTOPO_BUILD_FUZZERS=ON
//   cmake --build build-fuzz -j2 --target map_fuzzer
//   ASAN_OPTIONS=detect_leaks=0:quarantine_size_mb=16:malloc_context_size=5 UBSAN_OPTIONS=halt_on_error=1 \
//   build-fuzz/bin/map_fuzzer -jobs=5 -workers=1 -runs=100000 -max_len=4096 corpus/ tests/io/map_fuzz_seeds
// (doc/guarantees.md, "Fuzzing the map readers": why these options, the run's figures and what it found).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "map_fuzz_common.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path dir = [] {
    const auto d = std::filesystem::path("/dev/shm") / ("gridtopo_map_fuzzer_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string failure =
      gridtopo::test::mapFuzzOne(dir, std::string(reinterpret_cast<const char*>(data), size));
  if (!failure.empty()) {
    std::fprintf(stderr, "map_fuzzer: %s\n", failure.c_str());
    __builtin_trap();
  }
  return 0;
}
