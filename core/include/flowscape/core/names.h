#pragma once
// Suggestions for a misspelt name (a config key, a rig file's key, a lens parameter, an option).
#include <string>
#include <utility>
#include <vector>

namespace flowscape {

// Levenshtein distance, case-insensitive.
int edit_distance(const std::string& a, const std::string& b);
// " (did you mean \"x\"?)" for the known name x that `name` is an alias of (`aliases`: pairs of
// other spellings and the name they mean) or closest to (within a third of the longer name's
// length, at least 2 edits), or else " (known: a, b, c)".
std::string did_you_mean(const std::string& name, const std::vector<std::string>& known,
                         const std::vector<std::pair<std::string, std::string>>& aliases = {});

}  // namespace flowscape
