#pragma once
// SHA-256 (FIPS 180-4) of bytes and files, as lowercase hex: release manifests, and the fetched
// data (sky maps, weights) checked against their pinned hashes when loaded. None of the
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

// A fetched file checked against the sha256 its folder's SHA256SUMS pins (sha256sum's format,
// written by the script that fetched it: scripts/npm_fetch.sh), whenever it is read: a FileError
// naming the file when it differs (damaged since), or when the folder pins nothing for it.
void require_pinned(const std::filesystem::path& file);

}  // namespace flowscape
