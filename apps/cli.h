#pragma once
// What every app's command line shares: defaults shown in --help, and a bad option is one line on
// stderr, like every other error.
#include <CLI/CLI.hpp>
#include <string>

inline void finish_options(CLI::App& app, const std::string& name) {
  // called after the options are added: their variables hold the defaults now
  for (CLI::Option* option : app.get_options())
    if (option->get_default_str().empty()) option->capture_default_str();
  app.failure_message([name](const CLI::App*, const CLI::Error& e) {
    return name + ": error: " + e.what() + " (see --help)\n";
  });
}
