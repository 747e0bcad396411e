#pragma once
// --version of the apps that trace rays: flowscape's version with Embree's and the kernel family
// it runs here (FLOWSCAPE_EMBREE_CONFIG), so that releases from two machines can be compared.
#include <cstdio>
#include <cstdlib>

#include "cli.h"
#include "flowscape/core/files.h"
#include "flowscape/renderer/ray_kernels.h"

inline void version_with_kernels(CLI::App& app, const std::string& name) {
  app.set_version_flag("--version", [name] {
    try {
      return std::string("flowscape ") + FLOWSCAPE_VERSION + ", " +
             flowscape::describe(flowscape::ray_kernels());
    } catch (const std::exception& e) {
      std::fprintf(flowscape::diagnostics(), "%s: error: %s\n", name.c_str(), e.what());
      std::exit(kUsageError);
    }
  });
}
