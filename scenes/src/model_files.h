#pragma once
// Internal: what a model file must be before assimp reads it. assimp trusts a PLY header (a
// 150-byte truncated PLY aborts it; one declaring 10 M faces in 220 bytes takes 20 s and 740 MB),
// and reads an OBJ's group lines only as the format defines them.
#include <string>

namespace flowscape {

// Refuses a PLY file whose header declares more elements than the file can hold, or more than
// `max_elements` of one kind, naming the file and the element.
void check_ply(const std::string& path, std::size_t max_elements);

// An OBJ file whose faces come before their group lines (a "g name" after each group's faces,
// the last one followed by none: the classic Cornell box) rewritten with each group line ahead of
// its faces, as its authors meant, and its mtllib made absolute; "" for any other file.
std::string obj_with_groups_first(const std::string& path);

}  // namespace flowscape
