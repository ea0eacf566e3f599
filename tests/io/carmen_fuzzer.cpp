// libFuzzer target for the CARMEN parser (plain text and gzip input): every input must either parse or throw
// gridtopo::InputError. Build (clang only):
//   cmake -S . -B build-fuzz -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_BUILD_TYPE=RelWithDebInfo \
//         -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link,address,undefined" -DGRIDTOPO_BUILD_FUZZERS=ON
//   cmake --build build-fuzz -j2 --target carmen_fuzzer
//   build-fuzz/bin/carmen_fuzzer -max_total_time=60 -max_len=65536
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/io/carmen_log.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (const bool skip : {false, true}) {
    gridtopo::io::CarmenReadOptions o;
    o.skip_bad_lines = skip;
    o.read_rear_laser = true;
    try {
      std::istringstream in(text);
      const auto log = gridtopo::io::parseCarmenLog(in, "fuzz", o);
      for (const auto& r : log.scans)
        if (r.scan.valid.size() != r.scan.ranges.size() || r.scan.ranges.empty()) __builtin_trap();
    } catch (const gridtopo::InputError&) {
    }
  }
  return 0;
}
