#include "flowscape/layout/preview.h"

#include "flowscape/formats/contact_sheet.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/flow_viz.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/layout/classes.h"
#include "flowscape/layout/layout.h"

namespace flowscape {
namespace fs = std::filesystem;

std::vector<Image<std::uint8_t>> frame_preview_row(const fs::path& dir, int frame, int width,
                                                   const View& view, const std::string& classes,
                                                   FlowFormat flow_format) {
  const auto file = [&](const char* name) {
    ReleaseKind kind = output_kind(name);
    kind.flow_format = flow_format;
    return dir / frame_file(kind, view, frame);
  };
  const Image<std::uint8_t> color = read_image<std::uint8_t>(file("color"));
  Image<std::uint8_t> flow(color.width, color.height, 3);
  if (fs::exists(file("flow"))) {
    const Flow uv = read_flow(file("flow"));
    const Image<std::uint8_t> valid = read_image<std::uint8_t>(file("valid"));
    flow = flow_to_color(uv.uv.view(), valid.view(), {});
  }
  const Image<std::uint8_t> semantic = read_image<std::uint8_t>(file("semantic"));
  return {shrink_to_width(color, width), shrink_to_width(flow, width),
          shrink_to_width(table_colours(class_table(classes), semantic.view()), width)};
}

}  // namespace flowscape
