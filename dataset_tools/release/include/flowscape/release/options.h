#pragma once
// The release's options, each described once: its config.json key, the ReleaseConfig member it
// fills, its section, how the command line gives it, its range or choices, and its help. Reading
// and writing config.json, the checks of single values, gen_flowscape's options and
// docs/options.md are all made from this table (config.cpp, apps/gen_flowscape.cpp).
// Adding an option: a ReleaseConfig member, its row in release_options() (options.cpp), and the
// code that uses it; `gen_flowscape --options-markdown > docs/options.md` writes its docs.
#include <cstdint>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <variant>
#include <vector>

#include "flowscape/release/config.h"

namespace flowscape {

using OptionField =
    std::variant<int ReleaseConfig::*, std::uint64_t ReleaseConfig::*, double ReleaseConfig::*,
                 bool ReleaseConfig::*, std::string ReleaseConfig::*,
                 std::vector<int> ReleaseConfig::*, std::vector<double> ReleaseConfig::*,
                 std::vector<std::string> ReleaseConfig::*,
                 std::map<std::string, std::string> ReleaseConfig::*>;

enum class OptionSection { Plan, Scene, Render, Outputs, FinalPass, Rig };

// How the command line gives an option.
enum class OptionForm {
  Value,   // --flag VALUE
  List,    // --flag A,B,C: a list, comma-separated ("none": empty)
  Each,    // --flag A --flag B: repeated, each value through `parse` (an object) or as text
  Off,     // --no-thing: the bool false
  On,      // --thing: the bool true
  Parsed,  // --flag TEXT: `parse` gives the config keys it sets
  None,    // config files only
};

struct ReleaseOption {
  const char* key;  // in config.json
  OptionField field;
  OptionSection section;
  const char* flag = "";  // "--spp"
  OptionForm form = OptionForm::Value;
  // Numbers: the range a value must lie in, and what its special values mean ("0: uniform").
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  const char* special = "";
  std::vector<const char*> choices = {};  // text: the values it may take (none: checked elsewhere)
  const char* help = "";
  // Lists: what the command line wants ("whole numbers separated by commas, e.g. 1,2,4").
  const char* list_wants = "";
  std::size_t list_size = 0;  // > 0: exactly this many
  // Parsed: the text -> the config keys it sets ({"resolution": 512}); Each: one value -> an object
  // merged with the others'. Throw std::invalid_argument naming the option.
  nlohmann::json (*parse)(const std::string& text) = nullptr;
  // What a config.json without the key meant (a release from before the option): null, the
  // default; else the value those releases were made with.
  nlohmann::json absent = nullptr;
};

// Every option, by section.
const std::vector<ReleaseOption>& release_options();
std::string section_name(OptionSection section);  // "final pass"

// The option's value in a config, as config.json holds it.
nlohmann::json option_value(const ReleaseOption& option, const ReleaseConfig& config);
// Sets the option's member from JSON: exact integers, a list of integers, or the member's type.
// Throws std::invalid_argument naming the key.
void set_option(const ReleaseOption& option, const nlohmann::json& value, ReleaseConfig& config);
// Throws std::invalid_argument ("release config: spp must be in 1..65536") where the option's
// value leaves its range or choices.
void check_option(const ReleaseOption& option, const ReleaseConfig& config);
// A config.json as written by any earlier release, with the keys it lacks as `absent` says.
nlohmann::json with_absent_keys(nlohmann::json recorded);
// A list option's command-line text as config.json holds it; throws std::invalid_argument.
nlohmann::json parse_list(const ReleaseOption& option, const std::string& text);
// A repeated option's values (OptionForm::Each) as config.json holds them: each through `parse`
// into one object, or a list of the texts; throws std::invalid_argument.
nlohmann::json parse_each(const ReleaseOption& option, const std::vector<std::string>& values);

// docs/options.md: a table of every option per section.
std::string options_markdown();

}  // namespace flowscape
