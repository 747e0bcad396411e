// flowscape_preview: per sequence of a release, a contact sheet (first, middle and last flow frame:
// colour | flow | semantics) and an MP4 of colour and flow side by side.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "cli.h"
#include "flowscape/core/progress.h"
#include "flowscape/formats/contact_sheet.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/layout.h"
#include "flowscape/layout/meta.h"
#include "flowscape/layout/preview.h"
#include "flowscape/layout/split.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

// The views a preview shows: the ERP, or each camera of another rig (not the cube faces).
std::vector<View> shown_views(const ReleaseLayout& layout) {
  std::vector<View> views;
  for (const View& view : layout.views())
    if (!view.face) views.push_back(view);
  return views;
}

// Colour | flow of every shown view, one row each.
void write_video(const fs::path& path, const fs::path& sequence, const std::vector<View>& views,
                 int frames, int width, const std::string& classes, FlowFormat flow_format) {
  write_atomically(path, [&](const fs::path& temporary) {
    cv::VideoWriter video;
    for (int f = 0; f + 1 < frames; ++f) {
      std::vector<std::vector<Image<std::uint8_t>>> rows;
      for (const View& view : views) {
        const auto row = frame_preview_row(sequence, f, width, view, classes, flow_format);
        rows.push_back({row[0], row[1]});
      }
      const Image<std::uint8_t> tile = contact_sheet(rows);
      const cv::Mat rgb(tile.height, tile.width, CV_8UC3,
                        const_cast<std::uint8_t*>(tile.data.data()));
      if (!video.isOpened() &&
          !video.open(temporary.string(), cv::VideoWriter::fourcc('a', 'v', 'c', '1'), 30,
                      cv::Size(tile.width, tile.height)))
        throw FileError(path, "OpenCV cannot open an MP4 writer");
      cv::Mat bgr;
      cv::cvtColor(rgb, bgr, cv::COLOR_RGB2BGR);
      video.write(bgr);
    }
    video.release();
    // the encoder does not report failed writes (a full disk): read the video back
    cv::VideoCapture check(temporary.string());
    if (!check.isOpened() || check.get(cv::CAP_PROP_FRAME_COUNT) < frames - 1)
      throw FileError(path, "the MP4 encoder did not write every frame (disk full?)");
  });
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Contact sheets and MP4 previews of the sequences of a FlowScape release."};
  std::string release, out;
  std::vector<std::string> only;
  int width = 512;
  bool no_video = false;
  app.add_option("release", release, "release folder")->required();
  app.add_option("--sequences", only, "only these sequences (e.g. map00_seq05)");
  app.add_option("-o,--out", out, "output folder (default: <release>/previews)");
  app.add_option("--width", width, "width of each tile")->check(CLI::Range(16, 4096));
  app.add_flag("--no-video", no_video, "contact sheets only");
  finish_options(app, "flowscape_preview");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  if (out.empty()) out = (fs::path(release) / "previews").string();
  try {
    std::vector<SequenceInfo> sequences;
    for (const SequenceInfo& s : read_release_sequences(release))
      if (only.empty() || std::find(only.begin(), only.end(), s.name) != only.end())
        sequences.push_back(s);
    if (sequences.empty()) throw FileError(release, "no such sequences");
    remove_temporary_files(out);
    const ReleaseLayout layout = read_release_layout(release);
    const std::vector<View> views = shown_views(layout);
    const std::string classes = read_release_class_table(release);
    Progress progress("flowscape_preview", sequences.size(), "sequences");
    for (const SequenceInfo& s : sequences) {
      const fs::path dir = sequence_dir(release, s.name);
      std::vector<std::vector<Image<std::uint8_t>>> rows;
      for (int f : {0, (s.frames - 1) / 2, s.frames - 2})
        for (const View& view : views) {
          rows.push_back(frame_preview_row(dir, f, width, view, classes, layout.flow_format));
          const std::string camera = view.is_erp() ? "" : " " + view.camera;
          const std::string frame =
              s.name + camera + " (" + s.weather + ") frame " + std::to_string(f);
          for (const auto& [tile, what] :
               {std::pair{0, ": colour"}, {1, ": flow"}, {2, ": semantics"}})
            label_tile(rows.back()[tile], frame + what);
        }
      write_image(fs::path(out) / (s.name + ".png"), contact_sheet(rows));
      if (!no_video)
        write_video(fs::path(out) / (s.name + ".mp4"), dir, views, s.frames, width, classes,
                    layout.flow_format);
      progress.advance();
    }
    progress.finish();
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "flowscape_preview: error: %s\n", e.what());
    return 1;
  }
}
