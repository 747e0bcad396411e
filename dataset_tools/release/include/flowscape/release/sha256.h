#pragma once
// SHA-256 (FIPS 180-4) of bytes and files, as lowercase hex, for release manifests. None of the
// project's libraries offers it, so it is written here; tests check it against NIST's vectors and
// Python's hashlib.
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>

namespace flowscape {

class Sha256 {
 public:
  Sha256();
  void update(const void* data, std::size_t size);
  std::string hex();  // finishes the digest

 private:
  void block(const std::uint8_t* p);
  std::uint32_t state_[8];
  std::uint8_t buffer_[64];
  std::size_t buffered_ = 0;
  std::uint64_t length_ = 0;
};

std::string sha256_hex(std::string_view bytes);
std::string sha256_file(const std::filesystem::path& path);  // throws FileError

}  // namespace flowscape
