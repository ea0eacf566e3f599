#pragma once
// One fuzz input for the map readers (tests/io/map_fuzzer.cpp, tests/io/map_fuzz_test.cpp): the bytes are written
// as a ROS YAML (beside a small valid PGM), as a PGM and as a PNG, and each is read with readGridMap under a
// 10^6-cell budget. Every read must give a map or throw gridtopo::InputError naming the file on one line; anything
// else (another exception, a crash, a library's banner or call stack in the message) is a failure.
#include <filesystem>
#include <fstream>
#include <string>

#include "gridtopo/core/error.h"
#include "gridtopo/io/map_io.h"

namespace gridtopo::test {

/// Reads `bytes` as the three formats, each in its own folder under `dir` (so that no YAML stands beside the
/// images); returns "" when every read gave a map or a clean InputError, else what was wrong. `maps` counts the
/// reads that gave a map.
inline std::string mapFuzzOne(const std::filesystem::path& dir, const std::string& bytes, int* maps = nullptr) {
  namespace fs = std::filesystem;
  if (!fs::exists(dir / "yaml" / "base.pgm")) {
    for (const char* sub : {"yaml", "pgm", "png"}) fs::create_directories(dir / sub);
    std::ofstream(dir / "yaml" / "base.pgm", std::ios::binary) << "P5\n4 3\n255\n" << std::string(12, '\xfe');
  }
  io::MapReadOptions options;
  options.max_cells = 1'000'000;
  for (const char* name : {"yaml/fuzz.yaml", "pgm/fuzz.pgm", "png/fuzz.png"}) {
    const fs::path p = dir / name;
    std::ofstream(p, std::ios::binary | std::ios::trunc) << bytes;
    try {
      const auto g = io::readGridMap(p.string(), options);
      if (!g || g->getSizeX() == 0 || g->getSizeY() == 0) return std::string(name) + ": an empty map";
      if (maps) ++*maps;
    } catch (const InputError& e) {
      const std::string w = e.what();
      if (w.rfind(dir.string(), 0) != 0)
        return std::string(name) + ": the message does not name the file: " + w;
      if (w.find('\n') != std::string::npos) return std::string(name) + ": a message of several lines: " + w;
      // A library's banner or call stack (unless the input itself holds those words: messages quote values).
      for (const char* banner : {"====", "Call stack", "MRPT exception"})
        if (w.find(banner) != std::string::npos && bytes.find(banner) == std::string::npos)
          return std::string(name) + ": a library's banner in the message: " + w;
    } catch (const std::exception& e) {
      return std::string(name) + ": not an InputError: " + e.what();
    }
  }
  return "";
}

}  // namespace gridtopo::test
