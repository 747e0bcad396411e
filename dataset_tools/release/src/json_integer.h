#pragma once
// Internal: JSON integers read strictly, for release configs and shard manifests.
#include <cstdint>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace flowscape {

// A JSON number as an integer of type T in lo..hi, refusing fractions and values out of range by
// name (JSON numbers would otherwise be truncated or wrapped).
template <class T>
T json_integer(const nlohmann::json& value, const std::string& key,
               T lo = std::numeric_limits<T>::lowest(), T hi = std::numeric_limits<T>::max()) {
  const std::string name = "\"" + key + "\" ";
  if (!value.is_number_integer())
    throw std::invalid_argument(name + "must be an integer (got " + value.dump() + ")");
  bool fits;
  if (value.is_number_unsigned()) {
    const auto v = value.get<std::uint64_t>();
    fits = (lo <= T(0) || v >= std::uint64_t(lo)) && v <= std::uint64_t(hi);
  } else if (const auto v = value.get<std::int64_t>(); v >= 0) {  // stored signed, as C++ ints
    fits = (lo <= T(0) || std::uint64_t(v) >= std::uint64_t(lo)) &&
           std::uint64_t(v) <= std::uint64_t(hi);
  } else {
    fits = std::is_signed_v<T> && v >= std::int64_t(lo);
  }
  if (!fits)
    throw std::invalid_argument(name + value.dump() + " is out of range (" + std::to_string(lo) +
                                ".." + std::to_string(hi) + ")");
  return value.get<T>();
}

}  // namespace flowscape
