#pragma once
// Errors that name where bad input was found: file, line and field.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace gridtopo {

/// Bad input (a malformed log line, a wrong INI value, an unreadable map). what() reads
/// "<file>:<line>: <field>: <message>" (line and field omitted when unknown), the form compilers use,
/// so editors can jump to it.
class InputError : public std::runtime_error {
 public:
  InputError(std::string file, std::size_t line, std::string field, const std::string& message);
  InputError(std::string file, const std::string& message) : InputError(std::move(file), 0, "", message) {}

  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }  ///< 1-based; 0 when not line-oriented
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }

 private:
  std::string file_, field_, message_;
  std::size_t line_ = 0;
};

}  // namespace gridtopo
