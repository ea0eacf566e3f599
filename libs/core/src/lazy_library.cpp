#include "gridtopo/core/lazy_library.h"

#include <dlfcn.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace gridtopo {

std::string gridtopoLibrarySoname(const std::string& name) { return "libgridtopo_" + name + ".so." GRIDTOPO_SOVERSION; }

namespace {
// The folder holding this library (libgridtopo_core), where every gridtopo library lies (build tree and install).
std::filesystem::path coreLibraryFolder() {
  Dl_info info{};
  if (::dladdr(reinterpret_cast<void*>(&gridtopoLibrarySoname), &info) == 0 || !info.dli_fname) return {};
  return std::filesystem::path(info.dli_fname).parent_path();
}
}  // namespace

void* lazyLibrarySymbol(const std::string& name, const char* symbol) {
  if (void* loaded = ::dlsym(RTLD_DEFAULT, symbol)) return loaded;
  const std::string soname = gridtopoLibrarySoname(name);
  void* handle = nullptr;
  std::string why;
  const std::filesystem::path folder = coreLibraryFolder();
  if (!folder.empty() && std::filesystem::exists(folder / soname)) {
    handle = ::dlopen((folder / soname).c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (!handle) why = ::dlerror();
  }
  if (!handle) {
    handle = ::dlopen(soname.c_str(), RTLD_NOW | RTLD_GLOBAL);
    if (!handle && why.empty()) why = ::dlerror();
  }
  if (!handle) throw std::runtime_error("cannot load gridtopo's library " + soname + ": " + why);
  void* address = ::dlsym(handle, symbol);
  if (!address) throw std::runtime_error(soname + " has no function " + symbol + " (an older version?)");
  return address;
}

bool sharedLibraryLoaded(const std::string& prefix) {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line)) {
    const auto slash = line.rfind('/');
    if (slash != std::string::npos && line.compare(slash + 1, prefix.size(), prefix) == 0) return true;
  }
  return false;
}

}  // namespace gridtopo
