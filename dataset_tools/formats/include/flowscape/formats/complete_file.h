#pragma once
// Whether an output file that a resumed run would skip is whole: what the writers (write_file)
// guarantee for files they put in place, checked again because a file may come from an older
// version, another tool or a damaged disk.
#include <filesystem>

namespace flowscape {

// .png: signature and the IEND chunk at the very end; .flo: header and exact length; anything else
// (.exr, .jpg): decodes. Missing, empty or unreadable files are not complete.
bool is_complete_file(const std::filesystem::path& path);

}  // namespace flowscape
