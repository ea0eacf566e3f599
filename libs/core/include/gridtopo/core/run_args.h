#pragma once
// The command-line steps that the apps whose run is an INI file share (gridtopo-slam, gridtopo-topology,
// gridtopo-map): the positional RUN.ini, and the flags the user gave, which override single values of the RUN.ini.
#include <tclap/CmdLine.h>

#include <optional>
#include <string>

#include "gridtopo/core/app_shell.h"

namespace gridtopo {

/// The value of a flag the user gave; nothing when the flag was left out (its default does not override).
template <class Arg>
auto given(const Arg& arg) -> std::optional<std::decay_t<decltype(const_cast<Arg&>(arg).getValue())>> {
  if (!arg.isSet()) return std::nullopt;
  return const_cast<Arg&>(arg).getValue();
}

/// TCLAP hands an unknown flag to a positional argument: a positional text that starts with '-' is a UsageError
/// "<text>: unknown argument".
inline void rejectUnknownFlag(const std::string& text) {
  if (text.rfind('-', 0) == 0) throw UsageError(text + ": unknown argument");
}

/// The text of a positional argument (a RUN.ini or a map), rejectUnknownFlag checked.
inline std::string positionalArgument(const TCLAP::UnlabeledValueArg<std::string>& arg) {
  const std::string& text = const_cast<TCLAP::UnlabeledValueArg<std::string>&>(arg).getValue();
  rejectUnknownFlag(text);
  return text;
}

/// A RUN.ini, or the log (-i) and the output directory (-o) on the command line: UsageError "name the log (-i) and
/// the output directory (-o), or give a RUN.ini" when neither is given whole.
inline void requireRunIniOrInputOutput(const std::string& run_ini, bool has_input, bool has_output) {
  if (run_ini.empty() && (!has_input || !has_output))
    throw UsageError("name the log (-i) and the output directory (-o), or give a RUN.ini");
}

}  // namespace gridtopo
