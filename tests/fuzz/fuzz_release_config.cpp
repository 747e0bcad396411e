// A release config file: any JSON is a config or one std::invalid_argument naming the key.
#include <nlohmann/json.hpp>

#include "flowscape/core/files.h"
#include "flowscape/release/config.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const nlohmann::json json = nlohmann::json::parse(data, data + size, nullptr, false);
  if (json.is_discarded()) return 0;  // not JSON: read_json's error, not the config's
  try {
    flowscape::release_config_from_json(json);
  } catch (const std::invalid_argument&) {
  } catch (const flowscape::FileError&) {  // a "models" entry naming a missing file
  }
  return 0;
}
