#pragma once
// Cubemap folders as in the release: <cube dir>/<face>/<modality>/<frame file>, read into and
// written from one stacked image of N x 6N pixels (faces in kFaces order, see stitch.h).
#include <filesystem>
#include <string>
#include <vector>

#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/geometry/geometry.h"

namespace flowscape {

std::filesystem::path cube_file(const std::filesystem::path& cube_dir, Face face,
                                const std::string& modality, const std::string& file_name);

// The six faces of one frame, checked to share size, channels and pixel type.
AnyImage read_cube_image(const std::filesystem::path& cube_dir, const std::string& modality,
                         const std::string& file_name);
template <class T>
Image<T> read_cube_image_as(const std::filesystem::path& cube_dir, const std::string& modality,
                            const std::string& file_name);
// Flow of the folder `modality` ("flow", "flow_backward", "flow_gap2", ...).
Flow read_cube_flow(const std::filesystem::path& cube_dir, const std::string& modality,
                    const std::string& file_name);

template <class T>
void write_cube_image(const std::filesystem::path& cube_dir, const std::string& modality,
                      const std::string& file_name, ImageView<const T> stack);
void write_cube_flow(const std::filesystem::path& cube_dir, const std::string& modality,
                     const std::string& file_name, ImageView<const float> stack);

// File names (sorted) of one modality of the front face; empty when the folder is missing.
std::vector<std::string> cube_frame_files(const std::filesystem::path& cube_dir,
                                          const std::string& modality);

}  // namespace flowscape
