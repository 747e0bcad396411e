#include "model_files.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "flowscape/core/files.h"
#include "gltf_read.h"

namespace flowscape {
namespace {

constexpr std::size_t kMaxPlyHeader = 1 << 16;

// The bytes of a PLY property type, 0 for a type PLY does not have.
std::size_t ply_type_size(const std::string& type) {
  static const std::map<std::string, std::size_t> kSizes = {
      {"char", 1},   {"int8", 1},    {"uchar", 1},  {"uint8", 1},  {"short", 2}, {"int16", 2},
      {"ushort", 2}, {"uint16", 2},  {"int", 4},    {"int32", 4},  {"uint", 4},  {"uint32", 4},
      {"float", 4},  {"float32", 4}, {"double", 8}, {"float64", 8}};
  const auto found = kSizes.find(type);
  return found == kSizes.end() ? 0 : found->second;
}

// A property of a PLY element: a value of `size` bytes, or a list whose count takes `size` bytes
// and each item `item` bytes.
struct PlyProperty {
  std::size_t size = 0, item = 0;
  bool list = false;
};

struct PlyElement {
  std::string name;
  std::size_t count = 0;
  std::vector<PlyProperty> properties;
};

struct PlyHeader {
  bool ascii = false, big_endian = false;
  std::size_t length = 0;  // bytes up to and with end_header's line
  std::vector<PlyElement> elements;
};

PlyHeader ply_header(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  PlyHeader header;
  std::string line;
  if (!std::getline(in, line) || line.rfind("ply", 0) != 0) fail(path, "not a PLY file");
  header.length = line.size() + 1;
  while (std::getline(in, line)) {
    header.length += line.size() + 1;
    if (header.length > kMaxPlyHeader) fail(path, "a PLY header longer than 64 KB");
    std::istringstream words(line);
    std::string keyword;
    words >> keyword;
    if (keyword == "end_header") return header;
    if (keyword == "format") {
      std::string format;
      words >> format;
      header.ascii = format == "ascii", header.big_endian = format == "binary_big_endian";
    } else if (keyword == "element") {
      PlyElement element;
      if (!(words >> element.name >> element.count))
        fail(path, "PLY header: \"" + line + "\" is not element NAME COUNT");
      header.elements.push_back(element);
    } else if (keyword == "property" && !header.elements.empty()) {
      std::string type, item;
      words >> type;
      PlyProperty property;
      if (type == "list") words >> type >> item, property.list = true;
      property.size = ply_type_size(type), property.item = property.list ? ply_type_size(item) : 1;
      if (property.size == 0 || property.item == 0)
        fail(path, "PLY header: unknown property type in \"" + line + "\"");
      header.elements.back().properties.push_back(property);
    }
  }
  fail(path, "a PLY header without end_header");
}

// The rows of each element a binary body holds, walked as assimp reads them (each list's count
// read, its items skipped): the first element whose rows the file cuts short, or none.
void check_binary_rows(const std::string& path, const PlyHeader& header) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(std::streamoff(header.length));
  for (const PlyElement& e : header.elements)
    for (std::size_t row = 0; row < e.count; ++row)
      for (const PlyProperty& p : e.properties) {
        unsigned char bytes[8] = {};
        if (!in.read(reinterpret_cast<char*>(bytes), std::streamsize(p.size)))
          fail(path, "its header declares " + std::to_string(e.count) + " " + e.name +
                         " elements, the file holds " + std::to_string(row) + " (truncated?)");
        if (!p.list) continue;
        std::uint64_t items = 0;  // the list's count, in the file's byte order
        for (std::size_t k = 0; k < p.size; ++k)
          items |= std::uint64_t(bytes[header.big_endian ? p.size - 1 - k : k]) << (8 * k);
        in.seekg(std::streamoff(items * p.item), std::ios::cur);
      }
}

// Lines holding something after `offset`, counted up to `enough`.
std::size_t lines_after(const std::string& path, std::size_t offset, std::size_t enough) {
  std::ifstream in(path, std::ios::binary);
  in.seekg(std::streamoff(offset));
  std::size_t lines = 0;
  for (std::string line; lines < enough && std::getline(in, line);)
    lines += line.find_first_not_of(" \t\r") != std::string::npos;
  return lines;
}

bool starts(const std::string& line, const char* keyword) {
  const std::size_t start = line.find_first_not_of(" \t");
  if (start == std::string::npos) return false;
  const std::size_t length = std::char_traits<char>::length(keyword);
  return line.compare(start, length, keyword) == 0 &&
         (line.size() == start + length ||
          std::isspace(static_cast<unsigned char>(line[start + length])));
}

// A line of the rewritten OBJ: its material library found from anywhere.
std::string moved_line(const std::string& line, const std::filesystem::path& folder) {
  if (!starts(line, "mtllib")) return line + "\n";
  const std::size_t name = line.find_first_not_of(" \t", line.find("mtllib") + 6);
  return "mtllib " + (folder / line.substr(name)).string() + "\n";
}

}  // namespace

void check_ply(const std::string& path, std::size_t max_elements) {
  const PlyHeader header = ply_header(path);
  const std::uintmax_t body = std::filesystem::file_size(path) - header.length;
  std::uintmax_t rows = 0, least_bytes = 0;  // least_bytes: every list empty
  for (const PlyElement& e : header.elements) {
    if (e.count > max_elements)
      fail(path, "its header declares " + std::to_string(e.count) + " " + e.name +
                     " elements, more than a model may hold (" + std::to_string(max_elements) +
                     ")");
    rows += e.count;
    for (const PlyProperty& p : e.properties) least_bytes += e.count * p.size;
  }
  if (header.ascii) {
    const std::size_t lines = lines_after(path, header.length, rows);
    if (lines < rows)
      fail(path, "its header declares " + std::to_string(rows) +
                     " rows of elements, the file holds " + std::to_string(lines) +
                     " (truncated?)");
    return;
  }
  if (least_bytes > body)  // before walking it: a 220-byte file declaring millions of rows
    fail(path, "its header declares elements of at least " + std::to_string(least_bytes) +
                   " bytes, the file holds " + std::to_string(body) + " after it (truncated?)");
  check_binary_rows(path, header);
}

std::string obj_with_groups_first(const std::string& path) {
  std::istringstream in(read_file(path, std::uintmax_t(1) << 30));
  std::vector<std::string> lines;
  long first_face = -1, first_group = -1, last_group = -1, last_face = -1;
  for (std::string line; std::getline(in, line);) {
    const long k = long(lines.size());
    if (starts(line, "f")) last_face = k, first_face = first_face < 0 ? k : first_face;
    if (starts(line, "g") || starts(line, "o"))
      last_group = k, first_group = first_group < 0 ? k : first_group;
    lines.push_back(line);
  }
  if (first_group < 0 || first_face < 0 || first_face > first_group || last_face > last_group)
    return "";
  // each group line names the lines since the group line before it
  std::string out;
  std::size_t segment = 0;
  const std::filesystem::path folder = std::filesystem::absolute(path).parent_path();
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (!starts(lines[k], "g") && !starts(lines[k], "o")) continue;
    out += lines[k] + "\n";
    for (; segment < k; ++segment)
      if (!starts(lines[segment], "g") && !starts(lines[segment], "o"))
        out += moved_line(lines[segment], folder);
    segment = k + 1;
  }
  for (; segment < lines.size(); ++segment) out += moved_line(lines[segment], folder);
  return out;
}

}  // namespace flowscape
