#pragma once
// What every app's command line shares: defaults shown in --help, --version, and a bad option is
// one line on stderr, like every other error, with the nearest option suggested for a misspelt
// one, and one exit status for every usage error.
#include <CLI/CLI.hpp>
#include <optional>
#include <string>

#include "flowscape/core/names.h"

// The exit status of a bad command line (a missing or misspelt option, a bad value).
inline constexpr int kUsageError = 2;

inline void finish_options(CLI::App& app, const std::string& name) {
  // called after the options are added: their variables hold the defaults now
  for (CLI::Option* option : app.get_options())
    if (option->get_default_str().empty()) option->capture_default_str();
  app.set_version_flag("--version", std::string("flowscape ") + FLOWSCAPE_VERSION);
  app.failure_message([name](const CLI::App* failed, const CLI::Error& e) {
    std::string hint;
    std::vector<std::string> known;
    for (const CLI::Option* option : failed->get_options())
      for (const std::string& flag : option->get_lnames()) known.push_back("--" + flag);
    for (const std::string& extra : failed->remaining())
      if (extra.rfind("--", 0) == 0 && hint.empty())
        hint = "; " + extra + flowscape::did_you_mean(extra, known);
    return name + ": error: " + e.what() + hint + " (see --help)\n";
  });
}

// Parses the command line: nullopt to go on; else the status to exit with (0 after --help or
// --version, kUsageError after a usage error, its one line printed).
inline std::optional<int> parse_options(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
    return std::nullopt;
  } catch (const CLI::ParseError& e) {
    const int status = app.exit(e);
    return status == 0 ? 0 : kUsageError;
  }
}
