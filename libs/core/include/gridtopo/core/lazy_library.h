#pragma once
// One of gridtopo's shared libraries loaded when it is first needed, not at start.
//
// gridtopo-slam reads CARMEN logs and runs the filter without MRPT's maps and observations or OpenCV's image codecs:
// those two bring in about 170 shared libraries (GDAL, gdcm, assimp, ...) and some 60 MB of resident memory
// before the first scan is read. It needs them only to read an MRPT rawlog and to write the MRPT and image outputs at
// the end, and there it reaches them through lazyLibraryFunction: libgridtopo_io (rawlogs) and libgridtopo_slam (the
// output set). A program that links the library already (the GUI, gridtopo-map, the tests) uses its copy: nothing
// is loaded twice.
#include <string>

namespace gridtopo {

/// The address of the C symbol `symbol` of gridtopo's shared library `name` (`"io"`: libgridtopo_io.so.<soversion>):
/// from the process when a loaded library has it, else from the library loaded now (RTLD_NOW | RTLD_GLOBAL; never
/// unloaded) from the folder of libgridtopo_core (the build tree's lib/, an installation's lib folder), else from
/// the dynamic loader's search path. Throws std::runtime_error naming the library and the loader's reason when it
/// cannot be loaded or has no such symbol. Thread-safe (the dynamic loader's own lock).
void* lazyLibrarySymbol(const std::string& name, const char* symbol);

/// lazyLibrarySymbol as a function pointer of type `Fn` (the symbol must be an extern "C" function of that type).
template <class Fn>
Fn lazyLibraryFunction(const std::string& name, const char* symbol) {
  return reinterpret_cast<Fn>(lazyLibrarySymbol(name, symbol));
}

/// The file name of gridtopo's shared library `name` as the dynamic loader knows it (its SONAME).
std::string gridtopoLibrarySoname(const std::string& name);

/// True when a shared object whose file name starts with `prefix` (e.g. "libmrpt-maps.so") is mapped into this
/// process (/proc/self/maps); false where that file cannot be read.
bool sharedLibraryLoaded(const std::string& prefix);

}  // namespace gridtopo
