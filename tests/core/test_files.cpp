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

TEST_CASE("temporary names are write_file's pattern and nothing else") {
  CHECK(is_temporary_file(temporary_path("a/b/000001.flo")));
  CHECK(is_temporary_file("x/.partial-17-shard-1-of-2.json"));
  for (const char* other : {".partial-000001.flo", ".partial--x.png", ".partial-12-", "partial-1-x",
                            ".partial-1x-y.png", "notes.partial-1-x", ".partial-"})
    CHECK_FALSE(is_temporary_file(other));
}

TEST_CASE("temporary files a killed run left are removed, nothing else") {
  TempDir dir;
  const fs::path deep = dir.path / "a" / "b";
  write_text(deep / "keep.png", "x");
  std::ofstream(deep / ".partial-99-frame.png") << "half";
  std::ofstream(deep / ".partial-frame.png") << "not ours: no pid";
  std::ofstream(dir.path / "a" / ".partial-7-meta.json") << "half";
  std::ofstream(dir.path / ".partial-7-manifest.json") << "half";
  CHECK(remove_temporary_files(dir.path) == 1);  // this folder only
  CHECK_FALSE(fs::exists(dir.path / ".partial-7-manifest.json"));
  CHECK(fs::exists(dir.path / "a" / ".partial-7-meta.json"));
  CHECK(remove_temporary_files_under(dir.path) == 2);
  CHECK(fs::exists(deep / "keep.png"));
  CHECK(fs::exists(deep / ".partial-frame.png"));
  CHECK_FALSE(fs::exists(deep / ".partial-99-frame.png"));
  CHECK_FALSE(fs::exists(dir.path / "a" / ".partial-7-meta.json"));
  CHECK(remove_temporary_files(dir.path / "missing") == 0);  // nothing to do
  CHECK(remove_temporary_files_under(dir.path / "missing") == 0);
}

TEST_CASE("the temporaries of one file go, whoever wrote them; other files' stay") {
  TempDir dir;
  const fs::path shard = dir.path / "shard-1-of-2.json";
  for (const char* name : {".partial-5-shard-1-of-2.json", ".partial-66-shard-1-of-2.json",
                           ".partial-5-shard-11-of-2.json", ".partial-5-x-shard-1-of-2.json"})
    std::ofstream(dir.path / name) << "half";
  CHECK(remove_temporaries_of(shard) == 2);
  CHECK(fs::exists(dir.path / ".partial-5-shard-11-of-2.json"));
  CHECK(fs::exists(dir.path / ".partial-5-x-shard-1-of-2.json"));
}

TEST_CASE("FileError names the file first") {
  CHECK(std::string(FileError("x/y.flo", "truncated").what()) == "x/y.flo: truncated");
}
