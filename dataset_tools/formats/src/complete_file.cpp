#include "flowscape/formats/complete_file.h"

#include <array>
#include <cstring>
#include <fstream>

#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"

namespace flowscape {
namespace fs = std::filesystem;
namespace {

template <std::size_t N>
bool bytes_at(std::ifstream& in, std::streamoff offset, std::ios::seekdir from,
              const std::array<unsigned char, N>& expected) {
  std::array<char, N> found{};
  in.seekg(offset, from);
  return in.read(found.data(), N) && std::memcmp(found.data(), expected.data(), N) == 0;
}

bool png_complete(const fs::path& path) {
  static constexpr std::array<unsigned char, 8> kSignature = {0x89, 'P',  'N',  'G',
                                                              '\r', '\n', 0x1a, '\n'};
  // an empty IEND chunk: length 0, type, CRC
  static constexpr std::array<unsigned char, 12> kEnd = {0,   0,   0,    0,    'I',  'E',
                                                         'N', 'D', 0xae, 0x42, 0x60, 0x82};
  std::ifstream in(path, std::ios::binary);
  return fs::file_size(path) >= 20 && bytes_at(in, 0, std::ios::beg, kSignature) &&
         bytes_at(in, -12, std::ios::end, kEnd);
}

}  // namespace

bool is_complete_file(const fs::path& path) {
  std::error_code error;
  if (!fs::is_regular_file(path, error) || fs::file_size(path, error) == 0) return false;
  const std::string extension = path.extension().string();
  if (extension == ".png") return png_complete(path);
  try {
    if (extension == ".flo")
      read_flo(path);
    else
      read_any_image(path);
    return true;
  } catch (const FileError&) {
    return false;
  }
}

}  // namespace flowscape
