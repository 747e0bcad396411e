#include "flowscape/renderer/ray_kernels.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace flowscape {
namespace {

// What Embree 3.13's kernels of each family need (its isa.h: SSE2, SSE42, AVX, AVX2 (with
// AVXI's F16C and RDRAND), AVX512 (SKX)), each on top of the family before it; the compiler's
// checks include the operating system's support for the wider registers.
bool cpu_runs(const std::string& family) {
#if !defined(__x86_64__) && !defined(__i386__)
  return false;  // Embree runs its NEON translation there: one family, kNativeFamily
#else
  __builtin_cpu_init();
  if (family == "sse2") return __builtin_cpu_supports("sse") && __builtin_cpu_supports("sse2");
  if (family == "sse4.2")
    return __builtin_cpu_supports("sse3") && __builtin_cpu_supports("ssse3") &&
           __builtin_cpu_supports("sse4.1") && __builtin_cpu_supports("sse4.2") &&
           __builtin_cpu_supports("popcnt");
  if (family == "avx") return __builtin_cpu_supports("avx");
  if (family == "avx2")
    return __builtin_cpu_supports("f16c") && __builtin_cpu_supports("rdrnd") &&
           __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
           __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
           __builtin_cpu_supports("lzcnt");
  return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
         __builtin_cpu_supports("avx512cd") && __builtin_cpu_supports("avx512bw") &&
         __builtin_cpu_supports("avx512vl");
#endif
}

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return text;
}

std::vector<std::string> config_items(const std::string& config) {
  std::vector<std::string> items;
  std::string item;
  for (char c : config + ",") {
    if (c != ',' && c != ' ') {
      item += c;
    } else if (!item.empty()) {
      items.push_back(item);
      item.clear();
    }
  }
  return items;
}

struct ConfigError : std::invalid_argument {
  ConfigError(const std::string& config, const std::string& problem)
      : std::invalid_argument(std::string(kEmbreeConfigVariable) + "=\"" + config +
                              "\": " + problem) {}
};

int family_index(const std::string& config, const std::string& name) {
  const auto found = std::find(kKernelFamilies.begin(), kKernelFamilies.end(), name);
  if (found == kKernelFamilies.end())
    throw ConfigError(config, "unknown instruction set \"" + name + "\" (give one of " +
                                  joined(kKernelFamilies) + ")");
  return int(found - kKernelFamilies.begin());
}

constexpr const char* kNativeFamily = "native";  // a CPU other than x86's

struct CheckedConfig {
  std::string text;
  int family = 0;  // index into kKernelFamilies; -1: kNativeFamily
};

// Embree applies the items in order: isa= sets the family, max_isa= caps it.
CheckedConfig checked_config() {
  const char* given = std::getenv(kEmbreeConfigVariable);
  const std::string config = given ? given : "";
  const std::vector<std::string> cpu = cpu_kernel_families();
  CheckedConfig checked{config, int(cpu.size()) - 1};
  for (const std::string& item : config_items(config)) {
    const std::size_t equals = item.find('=');
    const std::string key = item.substr(0, equals), value = item.substr(equals + 1);
    if (equals == std::string::npos || value.empty())
      throw ConfigError(config, "\"" + item + "\" is not key=value");
    if (key == "isa" || key == "max_isa") {
      const int family = family_index(config, value);
      if (key == "isa" && family >= int(cpu.size()))
        throw ConfigError(config, "this CPU has no " + value + " (it runs " + joined(cpu) + ")");
      checked.family = key == "isa" ? family : std::min(checked.family, family);
    } else if (key == "threads" || key == "verbose" || key == "hugepages") {
      if (value.find_first_not_of("0123456789") != std::string::npos || value.size() > 4)
        throw ConfigError(config, key + " wants a whole number (got \"" + value + "\")");
    } else {
      throw ConfigError(config, "unknown key \"" + key +
                                    "\" (isa, max_isa, threads, verbose and hugepages are taken)");
    }
  }
  return checked;
}

}  // namespace

std::vector<std::string> cpu_kernel_families() {
  std::vector<std::string> families;
  for (const std::string& family : kKernelFamilies) {
    if (!cpu_runs(family)) break;
    families.push_back(family);
  }
  return families;
}

std::string embree_config() { return checked_config().text; }

RayKernels ray_kernels() {
  const CheckedConfig config = checked_config();
  RTCDevice device = rtcNewDevice(config.text.c_str());
  if (!device)
    throw std::runtime_error(std::string("Embree refused the device configuration ") +
                             kEmbreeConfigVariable + "=\"" + config.text + "\"");
  std::ostringstream version;
  version << rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MAJOR) << '.'
          << rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_MINOR) << '.'
          << rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_VERSION_PATCH);
  rtcReleaseDevice(device);
  const std::string family =
      config.family < 0 ? kNativeFamily : kKernelFamilies[std::size_t(config.family)];
  return {version.str(), family, config.text};
}

std::string describe(const RayKernels& kernels) {
  return "Embree " + kernels.embree + ", " + kernels.family + " kernels" +
         (kernels.config.empty()
              ? std::string()
              : " (" + std::string(kEmbreeConfigVariable) + "=" + kernels.config + ")");
}

}  // namespace flowscape
