#include "gridtopo/core/error.h"

namespace gridtopo {
namespace {
std::string format(const std::string& file, std::size_t line, const std::string& field, const std::string& msg) {
  std::string s = file.empty() ? std::string("<input>") : file;
  if (line > 0) s += ":" + std::to_string(line);
  s += ": ";
  if (!field.empty()) s += field + ": ";
  return s + msg;
}
}  // namespace

InputError::InputError(std::string file, std::size_t line, std::string field, const std::string& message)
    : std::runtime_error(format(file, line, field, message)),
      file_(std::move(file)),
      field_(std::move(field)),
      message_(message),
      line_(line) {}

}  // namespace gridtopo
