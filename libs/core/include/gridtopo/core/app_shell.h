#pragma once
// The one shell of every gridtopo command-line app: one error format and one set of exit codes.
//   0  success (also --help / --version);
//   1  bad input or a failed run: "<app>: error: <file>:<line>: <field>: <message>" (gridtopo::InputError) or
//      "<app>: error: <what>" (any other std::exception);
//   2  bad usage: an unknown or malformed argument (TCLAP) or a gridtopo::UsageError (e.g. options that exclude each
//      other): "<app>: usage: <message> (see <app> --help)".
// An app's main is `return gridtopo::runApp("gridtopo-x", [&] { ...; return 0; });`, with its TCLAP::CmdLine set to
// setExceptionHandling(false) so that TCLAP reports instead of exiting.
#include <tclap/CmdLine.h>

#include <exception>
#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>

#include "gridtopo/core/error.h"

namespace gridtopo {

/// Command-line arguments that parse but do not make sense together (exit code 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline int runApp(const std::string& app, const std::function<int()>& body) {
  try {
    return body();
  } catch (const TCLAP::ExitException& e) {  // --help, --version
    return e.getExitStatus();
  } catch (const TCLAP::ArgException& e) {
    std::cerr << app << ": usage: " << e.argId() << ": " << e.error() << " (see " << app << " --help)\n";
    return 2;
  } catch (const UsageError& e) {
    std::cerr << app << ": usage: " << e.what() << " (see " << app << " --help)\n";
    return 2;
  } catch (const std::exception& e) {  // InputError's what() is "file:line: field: message"
    std::cerr << app << ": error: " << e.what() << "\n";
    return 1;
  }
}

}  // namespace gridtopo
