// Release throughput: seconds per frame of the default FlowScape release (512 x 1024 ERP, six
// 256^2 cube faces, every modality written; colour at the default samples, denoised) on the first
// frames of one sequence, its set-up spread over a release sequence's 100 frames, and the
// projected time of the full 6,400-frame release on 2 cores (target: at most
// 2.7 h, about 1.5 s per frame). Baselines in the same run: the raw path tracer at 16 spp, the
// release's colour before the denoiser; the legacy actors (flowscape 0.9's boxes) against the
// detailed ones: their cost (target: at most 15 %); and the clean release against the same with
// the final pass (output kind "final": motion blur, camera): its cost (aim: at most 60 %), and
// where that release's time went by phase. Each pair measured alternately, median of
// max(runs, 3) each.
// First, flowscape 0.10's path (each frame written before the next renders, by 0.10's renderer:
// kEarlierPath) against the new one (writing a frame while the next renders, the renderer's
// levers on), with how many cores were busy, and where the new path's time went by phase; then
// each renderer lever on its own against 0.10's and 0.11's renderer (a TracingBaseline switches it
// back) on the first frame of each sequence of the fixed sample below, alternating, median of
// max(runs, 1), and whether any image changed.
// With `runs` > 0, first the same two paths over a fixed sample covering every map, weather and
// time of day, median of `runs` runs (issue 37's measure; about 8 x frames x 10 s per run).
// Usage: bench_release [frames = 4] [threads = 2] [runs = 0] [final | actors]
// ("final": only the clean release against the one with the final pass, and its phases;
// "actors": only the legacy actors against the detailed ones, and both's phases)
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "flowscape/core/profile.h"
#include "flowscape/release/final_pass.h"
#include "flowscape/release/sequence.h"
#include "flowscape/release/writer.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

// flowscape 0.10's path: each frame's files written before the next renders, its rays traced one by
// one and its scattered paths seeing the sky unaveraged.
constexpr TracingBaseline kEarlierPath{.single_rays = true, .full_sky_when_scattered = true};

// What `render` gives with the renderer tracing as `baseline` says, the renderer as it was after.
template <class Render>
auto traced_as(Renderer& renderer, const TracingBaseline& baseline, Render render) {
  renderer.trace_as(baseline);
  auto rendered = render();
  renderer.trace_as({});
  return rendered;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// A release's sequences of `release_frames` frames as the bench's few frames of some measure them.
struct Measured {
  double seconds_per_frame = 0;   // the frames' time less the set-up, plus the set-up spread
  double cores_busy = 0;          // CPU seconds over wall seconds while the sequences were written
  double cores_projected = 0;     // the same with the set-up (one core) spread as for the time
  std::vector<PhaseTime> phases;  // where that time went (core/profile.h)
  double wall = 0;                // seconds the sequences took to write
};

// Writes the planned sequences, each's set-up (its city, models and BVHs) timed on its own first.
Measured measure(const ReleaseConfig& config, const std::vector<SequencePlan>& plans,
                 const fs::path& out, int release_frames, const TracingBaseline* baseline) {
  double setup = 0, setup_cpu = 0, cpu = 0;
  Measured m;
  reset_phase_times();
  for (const SequencePlan& plan : plans) {
    fs::remove_all(out);
    const double setup_cpu_before = process_cpu_seconds();
    auto start = std::chrono::steady_clock::now();
    {
      const Sequence sequence = make_sequence(sequence_spec(config, plan));
      const Renderer renderer(sequence.city.scene);
    }
    setup += seconds_since(start);
    setup_cpu += process_cpu_seconds() - setup_cpu_before;
    const double cpu_before = process_cpu_seconds();
    start = std::chrono::steady_clock::now();
    write_sequence(config, plan, out, {[] {}, [] {}}, baseline);
    m.wall += seconds_since(start);
    cpu += process_cpu_seconds() - cpu_before;
  }
  fs::remove_all(out);
  m.cores_busy = cpu / m.wall;
  m.phases = phase_times();
  const double sequences = double(plans.size());
  m.seconds_per_frame =
      (m.wall - setup) / (config.frames * sequences) + setup / (release_frames * sequences);
  const double spread = double(config.frames) / release_frames;  // of a sequence's set-up
  m.cores_projected =
      ((cpu - setup_cpu) + setup_cpu * spread) / ((m.wall - setup) + setup * spread);
  return m;
}

Measured measure(const ReleaseConfig& config, const fs::path& out, int release_frames,
                 const TracingBaseline* baseline = nullptr) {
  return measure(config, {plan_sequences(config).front()}, out, release_frames, baseline);
}

double seconds_per_frame(const ReleaseConfig& config, const fs::path& out, int release_frames) {
  return measure(config, out, release_frames).seconds_per_frame;
}

// The fixed sample issue 37 measures on: one sequence per map, the weather and time of day cycling
// with the map (sunny by day, cloud at dusk, fog at night, rain at dawn, twice), so that every
// map, weather and time of day is in it.
std::vector<SequencePlan> fixed_sample(ReleaseConfig& config) {
  config.maps = kMapCount, config.sequences_per_map = 4;
  config.weathers = {"sunny", "cloud", "fog", "rain"};
  config.times_of_day = {"day", "dusk", "night", "dawn"};
  const std::vector<SequencePlan> all = plan_sequences(config);
  std::vector<SequencePlan> sample;
  for (int map = 0; map < kMapCount; ++map) sample.push_back(all[std::size_t(4 * map + map % 4)]);
  return sample;
}

Measured median(std::vector<Measured> all) {  // by seconds per frame
  std::sort(all.begin(), all.end(), [](const Measured& a, const Measured& b) {
    return a.seconds_per_frame < b.seconds_per_frame;
  });
  return all[all.size() / 2];
}

// The median run of `runs` over the fixed sample.
Measured median_run(const ReleaseConfig& config, const std::vector<SequencePlan>& sample,
                    const fs::path& out, int release_frames, const TracingBaseline* baseline,
                    int runs) {
  std::vector<Measured> all;
  for (int run = 0; run < runs; ++run)
    all.push_back(measure(config, sample, out, release_frames, baseline));
  return median(all);
}

// Two releases of map00_seq00 measured alternately, the median of `runs` each: their ratio over
// the same stretch of the machine's load.
std::pair<Measured, Measured> alternating(const ReleaseConfig& a, const ReleaseConfig& b,
                                          const fs::path& out, int release_frames, int runs) {
  std::vector<Measured> as, bs;
  for (int run = 0; run < runs; ++run) {
    as.push_back(measure(a, out, release_frames));
    bs.push_back(measure(b, out, release_frames));
  }
  return {median(as), median(bs)};
}

// Where the new path's time went: each phase's wall seconds per frame and share of the wall time
// (summed over threads: phases that overlap can add up to more than 100 %).
void print_profile(const Measured& m, int frames) {
  std::printf(
      "  where a frame's time goes (wall seconds per frame, share of the sequence's wall "
      "time; phases overlap):\n");
  for (const PhaseTime& p : m.phases)
    std::printf("    %-44s %6.3f s  %5.1f %%  (%ld calls)\n", p.name.c_str(), p.seconds / frames,
                100 * p.seconds / m.wall, p.calls);
}

// What a lever's render of one frame gave: its time, rays (colour only) and images.
struct Rendered {
  double seconds = 0;
  std::uint64_t rays = 0;
  std::vector<const std::vector<float>*> floats;  // into `colour` or `truth`
  std::vector<const std::vector<std::uint8_t>*> bytes;
  std::vector<const std::vector<std::uint16_t>*> words;
  std::vector<ColorLayers> colour;
  std::vector<GroundTruth> truth;
};

bool same_images(const Rendered& a, const Rendered& b) {
  const auto same = [](const auto& x, const auto& y) {
    for (std::size_t i = 0; i < x.size(); ++i)
      if (std::memcmp(x[i]->data(), y[i]->data(), x[i]->size() * sizeof((*x[i])[0])) != 0)
        return false;
    return true;
  };
  return same(a.floats, b.floats) && same(a.bytes, b.bytes) && same(a.words, b.words);
}

// Points out.floats at every layer of out.colour.
void compare_colour(Rendered& out) {
  for (const ColorLayers& l : out.colour)
    for (const Image<float>* layer :
         {&l.direct, &l.indirect, &l.specular, &l.other, &l.albedo, &l.normal, &l.variance})
      out.floats.push_back(&layer->data);
}

// The six faces' colour layers as trace(face's projection, its stats) gives them, timed.
template <class Trace>
Rendered traced_faces(int face_size, Trace&& trace) {
  Rendered out;
  const auto start = std::chrono::steady_clock::now();
  for (Face face : kFaces) {
    RenderStats stats;
    out.colour.push_back(trace(Projection::cube_face(face, face_size), stats));
    out.rays += stats.rays;
  }
  out.seconds = seconds_since(start);
  return out;
}

// The cube faces' path tracing of a frame (their colour layers).
Rendered faces_color(Renderer& renderer, int face_size, const FramePair& pair,
                     const RenderOptions& options) {
  Rendered out = traced_faces(face_size, [&](const Projection& face, RenderStats& stats) {
    return renderer.color_layers(face, pair, options, &stats);
  });
  compare_colour(out);
  return out;
}

// The six faces' colour over the frame's shutter, each sample at its own time (the final pass's
// path tracing, without its depth guide).
Rendered faces_over_shutter(Renderer& renderer, int face_size, const Sequence& sequence,
                            const Shutter& shutter, const RenderOptions& options) {
  const CameraTrack rig = [&](double t) { return sequence.city.rig(t); };
  return traced_faces(face_size, [&](const Projection& face, RenderStats& stats) {
    return renderer.color_layers(face, shutter, rig, {}, options, &stats);
  });
}

// The ground truth of a frame: the ERP's and the six faces'.
Rendered frame_truth(Renderer& renderer, const ReleaseConfig& config, const TruthRequest& request) {
  Rendered out;
  const auto start = std::chrono::steady_clock::now();
  out.truth.push_back(renderer.ground_truth(Projection::equirectangular(config.height), request));
  for (Face face : kFaces)
    out.truth.push_back(
        renderer.ground_truth(Projection::cube_face(face, config.face_size), request));
  out.seconds = seconds_since(start);
  for (const GroundTruth& t : out.truth) {
    for (const Image<float>* image :
         {&t.flow, &t.depth, &t.scene_flow, &t.normal, &t.shading_normal})
      out.floats.push_back(&image->data);
    out.bytes.push_back(&t.semantic.data), out.bytes.push_back(&t.valid.data);
    out.words.push_back(&t.instance.data);
    for (const FlowTruth& more : t.more)
      out.floats.push_back(&more.flow.data), out.bytes.push_back(&more.valid.data);
  }
  return out;
}

// A renderer lever: what it renders of a sequence's first frame the old way (flowscape 0.11's)
// and with the lever.
struct Lever {
  const char* name;
  Rendered (*render)(const ReleaseConfig&, const Sequence&, Renderer&, bool with_lever);
};
constexpr Lever kLevers[] = {
    {"the averaged sky after a diffuse event (colour)",
     [](const ReleaseConfig& config, const Sequence& sequence, Renderer& renderer, bool with) {
       return traced_as(renderer, {.full_sky_when_scattered = !with}, [&] {
         return faces_color(renderer, config.face_size, sequence.frame_pair(0),
                            sequence.color_options(color_section(config), 0));
       });
     }},
    {"ground truth's camera and visibility rays in packets",
     [](const ReleaseConfig& config, const Sequence& sequence, Renderer& renderer, bool with) {
       const TruthRequest request =
           truth_plan(sequence, release_layout(config), 0, config.frames).request;
       return traced_as(renderer, {.single_rays = !with},
                        [&] { return frame_truth(renderer, config, request); });
     }}};

// Each lever on its own against the old way, on the first frame of each sequence of the fixed
// sample, alternating, the median of `runs`, and whether every image stayed the same.
void print_render_levers(const ReleaseConfig& config, const std::vector<SequencePlan>& sample,
                         int runs) {
  runs = std::max(1, runs);
  std::printf(
      "  renderer levers, each against the way before it (0.11's renderer) on "
      "the first frames of the fixed sample, median of %d:\n",
      runs);
  for (const Lever& lever : kLevers) {
    double before = 0, after = 0;
    std::uint64_t rays = 0;
    bool same = true;
    for (const SequencePlan& plan : sample) {
      const Sequence sequence = make_sequence(sequence_spec(config, plan));
      Renderer renderer(sequence.city.scene);
      std::vector<double> times[2];
      lever.render(config, sequence, renderer, true);  // untimed: poses the targets' scenes
      for (int run = 0; run < runs; ++run) {
        const Rendered a = lever.render(config, sequence, renderer, false);
        const Rendered b = lever.render(config, sequence, renderer, true);
        times[0].push_back(a.seconds), times[1].push_back(b.seconds);
        same = same && same_images(a, b);
        if (run == 0) rays += a.rays;
      }
      for (auto& t : times) std::sort(t.begin(), t.end());
      before += times[0][times[0].size() / 2], after += times[1][times[1].size() / 2];
    }
    const double frames = double(sample.size());
    std::printf("    %-52s before %6.3f s/frame", lever.name, before / frames);
    if (rays > 0) std::printf(" (%5.2f M rays/s)", rays / before / 1e6);
    std::printf(", with it %6.3f s/frame: %+5.1f %%, %s\n", after / frames,
                100 * (after / before - 1), same ? "every byte the same" : "images changed");
  }
}

}  // namespace

// Over the fixed sample, `runs` times each: 0.10's path and the new one, projected to the full
// release, with where the new one's time went.
void print_fixed_sample(ReleaseConfig config, const fs::path& out, int full_frames,
                        int release_frames, int threads, int runs) {
  const std::vector<SequencePlan> sample = fixed_sample(config);
  std::printf(
      "  the fixed sample: %zu sequences (one per map; sunny day, cloud dusk, fog night, "
      "rain dawn), %d frames each, median of %d runs\n",
      sample.size(), config.frames, runs);
  const auto hours = [&](double seconds) { return seconds * full_frames / 3600; };
  const Measured old_path = median_run(config, sample, out, release_frames, &kEarlierPath, runs);
  const Measured new_path = median_run(config, sample, out, release_frames, nullptr, runs);
  for (const auto& [name, m] : {std::pair{"0.10's path", &old_path}, {"the new path", &new_path}})
    std::printf(
        "    %-14s %6.2f s/frame, cores busy %.2f of %d (%.2f with %d-frame sequences): full "
        "release %5.2f h (target <= 2.7 h, cores >= 1.85)\n",
        name, m->seconds_per_frame, m->cores_busy, threads, m->cores_projected, release_frames,
        hours(m->seconds_per_frame));
  print_profile(new_path, config.frames * int(sample.size()));
}

// The clean release against the same with the final pass, alternating, and where the latter's time
// went by phase.
void print_final_pass(const ReleaseConfig& config, const fs::path& out, int sequence_frames,
                      int pair_runs, int full_frames) {
  ReleaseConfig with_final = config;
  with_final.outputs.push_back("final");
  const auto [clean_measured, final_measured] =
      alternating(config, with_final, out, sequence_frames, pair_runs);
  const double clean = clean_measured.seconds_per_frame,
               final_pass = final_measured.seconds_per_frame;
  std::printf(
      "  with the final pass                      %6.2f s/frame against the clean release's %.2f "
      "(alternating, median of %d): it costs %+.1f %% (aim <= +60 %%), full release %5.2f h\n",
      final_pass, clean, pair_runs, 100 * (final_pass / clean - 1),
      final_pass * full_frames / 3600);
  print_profile(final_measured, config.frames);
  // the final pass's samples traced at the frame's time and over its shutter, alternating
  const Sequence sequence = make_sequence(sequence_spec(config, plan_sequences(config).front()));
  Renderer renderer(sequence.city.scene);
  const RenderOptions options = shutter_options(sequence.color_options(color_section(config), 0));
  const Shutter shutter = frame_shutter(final_pass_section(config), sequence, 0);
  std::vector<double> times[2];
  for (int run = 0; run < pair_runs; ++run) {
    times[0].push_back(
        faces_color(renderer, config.face_size, sequence.frame_pair(0), options).seconds);
    times[1].push_back(
        faces_over_shutter(renderer, config.face_size, sequence, shutter, options).seconds);
  }
  for (auto& t : times) std::sort(t.begin(), t.end());
  const double still = times[0][times[0].size() / 2], moving = times[1][times[1].size() / 2];
  std::printf(
      "  the six faces at the final pass's %d spp: at the frame's time %.3f s, over the shutter "
      "(a time per sample) %.3f s: %+.1f %% (median of %d)\n",
      options.samples_per_pixel, still, moving, 100 * (moving / still - 1), pair_runs);
}

// The legacy actors (flowscape 0.9's boxes) against the detailed ones, alternating: the detailed
// actors' cost (and with `phases`, where each's time went).
void print_actors(const ReleaseConfig& config, const fs::path& out, int sequence_frames,
                  int pair_runs, bool phases) {
  ReleaseConfig legacy = config;
  legacy.actors = "legacy";
  const auto [boxes_measured, actors_measured] =
      alternating(legacy, config, out, sequence_frames, pair_runs);
  const double boxes = boxes_measured.seconds_per_frame, actors = actors_measured.seconds_per_frame;
  std::printf(
      "  legacy actors (flowscape 0.9's boxes)    %6.2f s/frame against the detailed actors' %.2f "
      "(alternating, median of %d): they cost %+.1f %% (target <= +15 %%)\n",
      boxes, actors, pair_runs, 100 * (actors / boxes - 1));
  if (phases) {
    std::printf("  the boxes' phases:\n");
    print_profile(boxes_measured, config.frames);
    std::printf("  the detailed actors' phases:\n");
    print_profile(actors_measured, config.frames);
  }
}

int main(int argc, char** argv) {
  const int frames = argc > 1 ? std::atoi(argv[1]) : 4, threads = argc > 2 ? std::atoi(argv[2]) : 2;
  const int runs = argc > 3 ? std::atoi(argv[3]) : 0;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  ReleaseConfig config;  // the paper's FlowScape
  const int full_frames = config.maps * config.sequences_per_map * config.frames,
            sequence_frames = config.frames;
  config.maps = 1, config.sequences_per_map = 1, config.frames = frames;
  const fs::path out = fs::temp_directory_path() / "flowscape-bench-release";
  const int pair_runs = std::max(runs, 3);
  if (argc > 4 && std::strcmp(argv[4], "final") == 0) {
    print_final_pass(config, out, sequence_frames, pair_runs, full_frames);
    return 0;
  }
  if (argc > 4 && std::strcmp(argv[4], "actors") == 0) {
    print_actors(config, out, sequence_frames, pair_runs, true);
    return 0;
  }
  if (runs > 0) print_fixed_sample(config, out, full_frames, sequence_frames, threads, runs);
  std::printf("bench_release: %d frames of map00_seq00, %d threads, %d x %d ERP, %d^2 faces\n",
              frames, threads, config.height, 2 * config.height, config.face_size);
  const Measured serial = measure(config, out, sequence_frames, &kEarlierPath);
  const Measured overlapped = measure(config, out, sequence_frames, nullptr);
  const double release = overlapped.seconds_per_frame;
  std::printf(
      "  0.10's path (writing after rendering)     %6.2f s/frame, cores busy %.2f of %d (%.2f "
      "with %d-frame sequences)\n",
      serial.seconds_per_frame, serial.cores_busy, threads, serial.cores_projected,
      sequence_frames);
  std::printf(
      "  the new path (writing while rendering)    %6.2f s/frame, cores busy %.2f of %d (%.2f "
      "with %d-frame sequences; target >= 1.85 of 2): %+.1f %%\n",
      release, overlapped.cores_busy, threads, overlapped.cores_projected, sequence_frames,
      100 * (release / serial.seconds_per_frame - 1));
  print_profile(overlapped, frames);
  {
    ReleaseConfig sampled = config;
    print_render_levers(sampled, fixed_sample(sampled), runs);
  }
  print_actors(config, out, sequence_frames, pair_runs, false);
  ReleaseConfig raw = config;
  raw.spp = raw.indirect_spp = 16, raw.denoise = "none";  // every sample indirect
  const double baseline = seconds_per_frame(raw, out, sequence_frames);
  const auto hours = [&](double seconds) { return seconds * full_frames / 3600; };
  std::printf("  default: %d spp (%d indirect), a-trous   %6.2f s/frame  full release %5.2f h\n",
              config.spp, indirect_samples(color_section(config)), release, hours(release));
  std::printf("  baseline: 16 spp raw                     %6.2f s/frame  full release %5.2f h\n",
              baseline, hours(baseline));
  std::printf("  %d frames: %.2f h, %.2fx the baseline (target <= 2.7 h on 2 cores)\n", full_frames,
              hours(release), release / baseline);
  print_final_pass(config, out, sequence_frames, pair_runs, full_frames);
  return 0;
}
