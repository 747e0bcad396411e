#pragma once
// Which Embree the renderer traces with and which of its kernel families runs, chosen at run time
// by FLOWSCAPE_EMBREE_CONFIG: Embree's device configuration, for instance "isa=avx2", so that one
// machine can run every family its CPU has (docs/renderer.md, "Embree's kernels").
#include <string>
#include <vector>

namespace flowscape {

inline constexpr const char* kEmbreeConfigVariable = "FLOWSCAPE_EMBREE_CONFIG";

// Embree's kernel families, lowest first: each runs on a CPU that runs the one after it.
inline const std::vector<std::string> kKernelFamilies = {"sse2", "sse4.2", "avx", "avx2", "avx512"};

struct RayKernels {
  std::string embree;  // Embree's version as the library reports it, "3.13.5"
  std::string family;  // the kernel family it runs: one of kKernelFamilies ("native" off x86)
  std::string config;  // FLOWSCAPE_EMBREE_CONFIG as given, "" when unset
};

// The kernel families this CPU (and its operating system) can run, lowest first.
std::vector<std::string> cpu_kernel_families();
// FLOWSCAPE_EMBREE_CONFIG, checked: only the keys docs/renderer.md lists, ISA names Embree knows
// (it would fall back to SSE2 for a misspelt one) and that this CPU runs. Throws
// std::invalid_argument naming the variable and the problem.
std::string embree_config();
// The Embree the renderer runs now, with the family that embree_config() selects.
RayKernels ray_kernels();
// "Embree 3.13.5, avx2 kernels (FLOWSCAPE_EMBREE_CONFIG=isa=avx2)": for --version.
std::string describe(const RayKernels& kernels);

}  // namespace flowscape
