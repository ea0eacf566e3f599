#pragma once
// SHA-256 (OpenSSL) of a text or of a file's bytes, as lowercase hex: the key of a run (its full options and the
// contents of its input files) under which finished runs are found again.
#include <string>

namespace gridtopo::experiment {

std::string sha256Hex(const std::string& data);
/// Hash of the file's bytes; an unreadable file is an InputError naming it.
std::string sha256OfFile(const std::string& path);

}  // namespace gridtopo::experiment
