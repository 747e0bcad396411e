#include "flowscape/release/layout.h"

#include <cstdio>
#include <stdexcept>

namespace flowscape {
namespace fs = std::filesystem;
namespace {

// The layout's names and templates; layout_json() states the same as str.format templates.
constexpr const char* kSplitsDir = "splits";

std::string numbered(const char* format, int value) {
  char text[32];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

const char* pixel_type_name(PixelType type) {
  switch (type) {
    case PixelType::UInt8:
      return "uint8";
    case PixelType::UInt16:
      return "uint16";
    case PixelType::Float32:
      return "float32";
  }
  return "";
}

const char* resampling_name(Resampling resampling) {
  switch (resampling) {
    case Resampling::Bilinear:
      return "bilinear";
    case Resampling::Nearest:
      return "nearest";
    case Resampling::Flow:
      return "flow";
  }
  return "";
}

}  // namespace

const OutputKind& output_kind(std::string_view name) {
  for (const OutputKind& kind : kOutputKinds)
    if (kind.name == name) return kind;
  throw std::invalid_argument("unknown output kind \"" + std::string(name) + "\"");
}

bool has_frame(const OutputKind& kind, int frame, int frames) {
  return frame >= 0 && frame < frames - (kind.pairs_only ? 1 : 0);
}

std::string sequence_name(int map, int sequence) {
  return numbered("map%02d", map) + numbered("_seq%02d", sequence);
}

std::string frame_name(int frame) { return numbered("%06d", frame); }

fs::path sequence_dir(const fs::path& release, const std::string& name) {
  return release / kSequencesDir / name;
}

fs::path view_dir(View view) {
  return view ? fs::path(kCubeDir) / std::string(face_name(*view)) : fs::path(kErpDir);
}

fs::path frame_file(const OutputKind& kind, View view, int frame) {
  return view_dir(view) / std::string(kind.folder) /
         (frame_name(frame) + std::string(kind.extension));
}

fs::path erp_file(const fs::path& sequence, std::string_view kind, int frame) {
  return sequence / frame_file(output_kind(kind), std::nullopt, frame);
}

std::vector<fs::path> frame_files(int frame, int frames, bool cube) {
  std::vector<fs::path> files;
  std::vector<View> views{std::nullopt};
  if (cube) views.insert(views.end(), kFaces.begin(), kFaces.end());
  for (const View& view : views)
    for (const OutputKind& kind : kOutputKinds)
      if ((view ? kind.cube : kind.erp) && has_frame(kind, frame, frames))
        files.push_back(frame_file(kind, view, frame));
  return files;
}

std::vector<fs::path> sequence_files(int frames, bool cube) {
  std::vector<fs::path> files{kMetaFile};
  for (int f = 0; f < frames; ++f) {
    const std::vector<fs::path> frame = frame_files(f, frames, cube);
    files.insert(files.end(), frame.begin(), frame.end());
  }
  return files;
}

fs::path split_file(const fs::path& release, const std::string& side) {
  return release / kSplitsDir / (side + ".txt");
}

nlohmann::json layout_json() {
  nlohmann::json kinds = nlohmann::json::array();
  for (const OutputKind& k : kOutputKinds)
    kinds.push_back({{"name", k.name},
                     {"folder", k.folder},
                     {"extension", k.extension},
                     {"pixel_type", pixel_type_name(k.pixel)},
                     {"channels", k.channels},
                     {"resampling", resampling_name(k.resampling)},
                     {"erp", k.erp},
                     {"cube", k.cube},
                     {"pairs_only", k.pairs_only},
                     {"description", k.description}});
  nlohmann::json faces = nlohmann::json::array();
  for (Face face : kFaces) faces.push_back(face_name(face));
  return {{"sequence_dir", std::string(kSequencesDir) + "/{sequence}"},
          {"meta", kMetaFile},
          {"views", {{"erp", kErpDir}, {"cube", std::string(kCubeDir) + "/{face}"}}},
          {"faces", faces},
          {"frame_file", "{view}/{folder}/{frame:06d}{extension}"},
          {"split_file", std::string(kSplitsDir) + "/{split}.txt"},
          {"kinds", kinds}};
}

}  // namespace flowscape
