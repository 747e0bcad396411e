// gt_quality throughput at 512 x 1024: pairs per second of the whole evaluation next to the time
// to only decode the same files (two PNGs and a .flo per pair). Target: within 1.5x of decoding.
// Usage: bench_gt_quality [pairs] [threads]
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "flowscape/formats/flow_io.h"
#include "flowscape/formats/image_io.h"
#include "flowscape/quality/gt_quality.h"

using namespace flowscape;
namespace fs = std::filesystem;

namespace {

constexpr int kH = 512, kW = 1024;

Image<std::uint8_t> frame(int k) {  // a textured panorama turning by k pixels, with some noise
  Image<std::uint8_t> image(kW, kH, 3);
  std::uint32_t state = 12345u + k;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      for (int c = 0; c < 3; ++c) {
        state = state * 1664525u + 1013904223u;
        const double v = 128 + 70 * std::sin(0.05 * (x - 2 * k) + c) * std::cos(0.07 * y) +
                         20 * std::sin(0.31 * (x - 2 * k) + 0.17 * y) + (state >> 28);
        image.pixel(x, y)[c] = std::uint8_t(std::clamp(v, 0.0, 255.0));
      }
  return image;
}

double seconds(const std::function<void()>& work) {
  const auto start = std::chrono::steady_clock::now();
  work();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv) {
  const int pairs = argc > 1 ? std::atoi(argv[1]) : 16, threads = argc > 2 ? std::atoi(argv[2]) : 2;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  const fs::path dir = fs::temp_directory_path() / "flowscape-bench-gt-quality";
  fs::remove_all(dir);
  Image<float> flow(kW, kH, 2);
  for (std::size_t i = 0; i < flow.pixel_count(); ++i)
    flow.data[2 * i] = 2, flow.data[2 * i + 1] = 0;
  for (int k = 0; k <= pairs; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "%06d", k);
    write_image(dir / "img" / (std::string(name) + ".png"), frame(k));
    if (k < pairs) write_flo(dir / "flow" / (std::string(name) + ".flo"), flow.view());
  }
  const FlowDataset dataset =
      glob_flow_dataset((dir / "img" / "*.png").string(), (dir / "flow" / "*.flo").string(), true);
  const double decode = seconds([&] {
    tbb::parallel_for(std::size_t(0), dataset.pairs.size(), [&](std::size_t k) {
      read_any_image(dataset.pairs[k].image1), read_any_image(dataset.pairs[k].image2);
      read_flow(dataset.pairs[k].flow);
    });
  });
  QualityReport report;
  const double full = seconds([&] { report = evaluate_quality(dataset, {{}, false}); });
  std::printf("bench_gt_quality: %d pairs of %d x %d (2 PNGs + .flo each), %d threads\n", pairs, kH,
              kW, threads);
  std::printf("  baseline: decoding only       %7.2f pairs/s\n", pairs / decode);
  std::printf(
      "  gt_quality (decode + PE/WPE)  %7.2f pairs/s   = %.2fx the decoding time (target <= "
      "1.5x)\n",
      pairs / full, full / decode);
  std::printf("  (PE %.2f, WPE %.2f)\n", report.rows[0].pe, report.rows[0].wpe);
  fs::remove_all(dir);
  return 0;
}
