#pragma once
// What every app's command line shares: a bad option is one line on stderr, like every other error.
#include <CLI/CLI.hpp>
#include <string>

inline void one_line_errors(CLI::App& app, const std::string& name) {
  app.failure_message([name](const CLI::App*, const CLI::Error& e) {
    return name + ": error: " + e.what() + " (see --help)\n";
  });
}
