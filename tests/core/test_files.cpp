#include <unistd.h>

#include <catch2/catch.hpp>
#include <fstream>
#include <sstream>

#include "flowscape/core/files.h"
#include "temp_dir.h"

using namespace flowscape;
namespace fs = std::filesystem;

TEST_CASE("an atomic write leaves the whole new file or the old one, never a part") {
  TempDir dir;
  const fs::path file = dir.path / "sub" / "notes.json";
  write_text(file, "first\n");
  CHECK(file_bytes(file) == "first\n");
  CHECK(temporary_path(file) ==
        dir.path / "sub" / (".partial-" + std::to_string(getpid()) + "-notes.json"));
  CHECK_THROWS_WITH(write_atomically(file,
                                     [](const fs::path& temporary) {
                                       std::ofstream(temporary) << "half";
                                       throw FileError(temporary, "disk on fire");
                                     }),
                    Catch::Contains("disk on fire"));
  CHECK(file_bytes(file) == "first\n");
  CHECK_FALSE(fs::exists(temporary_path(file)));
  write_text(file, "second\n");
  CHECK(file_bytes(file) == "second\n");
}

TEST_CASE("temporary files a killed run left are removed, nothing else") {
  TempDir dir;
  write_text(dir.path / "a" / "b" / "keep.png", "x");
  std::ofstream(dir.path / "a" / "b" / ".partial-frame.png") << "half";
  std::ofstream(dir.path / "a" / ".partial-meta.json") << "half";
  remove_temporary_files(dir.path);
  CHECK(fs::exists(dir.path / "a" / "b" / "keep.png"));
  CHECK_FALSE(fs::exists(dir.path / "a" / "b" / ".partial-frame.png"));
  CHECK_FALSE(fs::exists(dir.path / "a" / ".partial-meta.json"));
  remove_temporary_files(dir.path / "missing");  // nothing to do
}

TEST_CASE("FileError names the file first") {
  CHECK(std::string(FileError("x/y.flo", "truncated").what()) == "x/y.flo: truncated");
}
