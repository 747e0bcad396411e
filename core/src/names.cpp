#include "flowscape/core/names.h"

#include <algorithm>
#include <cctype>

namespace flowscape {

int edit_distance(const std::string& a, const std::string& b) {
  std::vector<int> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = int(j);
  for (std::size_t i = 1; i <= a.size(); ++i) {
    int diagonal = row[0];
    row[0] = int(i);
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                        std::tolower(static_cast<unsigned char>(b[j - 1]));
      const int next = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
      diagonal = row[j], row[j] = next;
    }
  }
  return row[b.size()];
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& known,
                         const std::vector<std::pair<std::string, std::string>>& aliases) {
  for (const auto& [alias, meant] : aliases)
    if (edit_distance(alias, name) == 0) return " (did you mean \"" + meant + "\"?)";
  const std::string* best = nullptr;
  int best_distance = 0;
  for (const std::string& candidate : known) {
    const int d = edit_distance(name, candidate);
    if (!best || d < best_distance) best = &candidate, best_distance = d;
  }
  const int allowed = std::max(2, int(std::max(name.size(), best ? best->size() : 0)) / 3);
  if (best && best_distance <= allowed) return " (did you mean \"" + *best + "\"?)";
  std::string list;
  for (const std::string& candidate : known) list += (list.empty() ? "" : ", ") + candidate;
  return " (known: " + list + ")";
}

}  // namespace flowscape
