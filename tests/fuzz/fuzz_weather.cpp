// A weather record (meta.json's "weather"): any JSON is a Weather or one std::invalid_argument.
#include <nlohmann/json.hpp>

#include "flowscape/core/files.h"
#include "flowscape/weather/weather.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const nlohmann::json json = nlohmann::json::parse(data, data + size, nullptr, false);
  if (json.is_discarded()) return 0;
  try {
    flowscape::weather_environment(flowscape::weather_from_json(json));
  } catch (const std::invalid_argument&) {
  }
  return 0;
}
