// flowscape_scenarios: scenarios from Python (flowscape/scenario.py) over the release library:
// a frame's preview and a release rendered from scenarios. A module of its own, so that the
// plugin's flowscape_native keeps linking the formats library alone.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "flowscape/core/files.h"
#include "flowscape/formats/srgb.h"
#include "flowscape/release/scenario.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/writer.h"

namespace py = pybind11;
using namespace flowscape;

namespace {

// The config a scenario renders in: the defaults, the scenario's release-wide keys, `options`.
ReleaseConfig preview_config(const Scenario& scenario, const std::string& options) {
  ReleaseConfig config = release_config_from_json(release_keys(scenario));
  return release_config_from_json(nlohmann::json::parse(options), config);
}

// The sequence's frame through an ERP `height` pixels high, colour as a release renders it
// (sRGB, H x W x 3 uint8).
py::array preview(const std::string& scenario_json, int frame, int height,
                  const std::string& options) {
  const Scenario scenario = scenario_from_json(nlohmann::json::parse(scenario_json));
  const ReleaseConfig config = preview_config(scenario, options);
  if (frame < 0 || frame + 1 >= config.frames)
    throw std::invalid_argument("frame " + std::to_string(frame) + ": the sequence has " +
                                std::to_string(config.frames) + " frames");
  const Sequence sequence = make_sequence(sequence_spec(config, scenario));
  Renderer renderer(sequence.city.scene);
  const Projection erp = Projection::equirectangular(height);
  const GroundTruth truth = renderer.ground_truth(erp, sequence.frame_pair(frame));
  const Image<std::uint8_t> srgb = linear_to_srgb8(
      release_color(color_section(config), sequence, renderer, erp, frame, truth).view());
  py::array_t<std::uint8_t> out({srgb.height, srgb.width, srgb.channels});
  std::copy(srgb.data.begin(), srgb.data.end(), out.mutable_data());
  return out;
}

// A release of the scenario files in `out`, with the config keys `options` (JSON) on top, as
// gen_flowscape --scenario FILE... makes it (resumable: the same call again finishes it).
py::dict render_release(const std::vector<std::string>& files, const std::string& out,
                        const std::string& options) {
  ConfigSources sources;
  sources.scenarios.assign(files.begin(), files.end());
  sources.command_line = nlohmann::json::parse(options);
  const ReleaseWritten written = write_release(resolve_config(sources), out);
  py::dict summary;
  summary["manifest"] = written.manifest.string();
  summary["sequences"] = written.sequences, summary["frames"] = written.frames;
  summary["files"] = written.files;
  return summary;
}

}  // namespace

PYBIND11_MODULE(flowscape_scenarios, m) {
  m.doc() = "FlowScape scenarios: previews and releases (flowscape/scenario.py wraps these)";
  py::register_exception<FileError>(m, "FileError", PyExc_ValueError);
  m.def("preview", &preview, py::arg("scenario_json"), py::arg("frame"), py::arg("height"),
        py::arg("options"));
  m.def("render_release", &render_release, py::arg("files"), py::arg("out"), py::arg("options"));
}
