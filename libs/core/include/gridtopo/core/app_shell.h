#pragma once
// The one shell of every gridtopo command-line app: one error format and one set of exit codes.
//   0  success (also --help / --help-options / --version);
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
#include "gridtopo/core/output_set.h"

namespace gridtopo {

/// Command-line arguments that parse but do not make sense together (exit code 2).
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// `--help-options` of an app whose run is an INI file: prints `text()` (every key of its sections with default,
/// range, unit and help, from the options' key tables) to stdout and exits 0 as --help does, before any other
/// argument is checked. Declare it beside the other arguments: `HelpOptionsArg help_options(cmd, slam::slamOptionsHelp);`
class HelpOptionsArg {
 public:
  HelpOptionsArg(TCLAP::CmdLine& cmd, std::function<std::string()> text)
      : print_(std::move(text)),
        arg_("", "help-options", "list every key of the run's INI sections (default, range, unit, help) and exit", cmd,
             false, &print_) {}

 private:
  struct Print : TCLAP::Visitor {
    explicit Print(std::function<std::string()> t) : text(std::move(t)) {}
    void visit() override {
      std::cout << text();
      throw TCLAP::ExitException(0);
    }
    std::function<std::string()> text;
  };
  Print print_;
  TCLAP::SwitchArg arg_;
};

inline int runApp(const std::string& app, const std::function<int()>& body) {
  installOutputCleanupOnSignals();  // SIGINT / SIGTERM / SIGHUP remove the uncommitted outputs' temporaries
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
