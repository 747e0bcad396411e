// flowviz: a flow file (.flo, KITTI .png, .exr) -> colour-coded PNG.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <map>

#include "cli.h"
#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/flow_viz.h"
#include "flowscape/formats/image_io.h"

using namespace flowscape;

int main(int argc, char** argv) {
  CLI::App app{
      "Colour-code an optical-flow file (.flo, KITTI 16-bit .png, .exr) as a PNG on the "
      "Middlebury wheel. Unknown or invalid flow is black."};
  std::string input, output;
  FlowVizOptions options;
  const std::map<std::string, FlowWheel> wheels{{"panoflow", FlowWheel::PanoFlow},
                                                {"middlebury", FlowWheel::Middlebury}};
  app.add_option("flow", input, "flow file")->required();
  app.add_option("-o,--out", output, "PNG to write (default: the input name with .png, beside it)");
  app.add_option("--wheel", options.wheel,
                 "panoflow: magnitudes above the scale lose saturation (the paper's figures); "
                 "middlebury: the classic wheel, normalised by the largest flow")
      ->transform(CLI::CheckedTransformer(wheels, CLI::ignore_case))
      ->default_str("panoflow");
  app.add_option("--scale", options.scale,
                 "flow magnitude (px) drawn fully saturated; 0 picks it from the flow")
      ->check(CLI::Range(0.0, 1e6));
  finish_options(app, "flowviz");
  if (const auto status = parse_options(app, argc, argv)) return *status;
  if (output.empty()) {
    std::filesystem::path out = input;
    output = out.replace_extension(out.extension() == ".png" ? ".viz.png" : ".png").string();
  }
  try {
    const Flow flow = read_flow(input);
    write_image(output, flow_to_color(flow.uv.view(), flow.valid.view(), options));
    std::printf("%s\n", output.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(diagnostics(), "flowviz: error: %s\n", e.what());
    return 1;
  }
}
