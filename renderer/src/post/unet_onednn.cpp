// OIDN's U-Net (RenderKit/oidn training/model.py): its forward pass on oneDNN.
#include <omp.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <map>
#include <mutex>
#include <oneapi/dnnl/dnnl.hpp>
#include <stdexcept>
#include <tuple>
#include <unordered_map>

#include "flowscape/renderer/neural_denoise.h"

namespace flowscape {

bool neural_denoiser_built() { return true; }

namespace {

using dnnl::memory;
using Tag = memory::format_tag;
using Type = memory::data_type;

constexpr int kAlignment = 16, kTileCore = 256, kOverlap = 64, kTile = kTileCore + 2 * kOverlap;

// The U-Net's primitives for one tile size, with its weights reordered for them. Tensors are
// numbered; operations name the tensors they read and write.
class Network {
 public:
  Network(const dnnl::engine& engine, const UNetWeights& weights, int height, int width)
      : engine_(engine) {
    dnnl::stream stream(engine_);
    const auto& L = weights.layers;
    const int input = add({1, L[0].in_channels, height, width}, Tag::nhwc);
    int x = conv(stream, L[0], input, true);
    x = conv(stream, L[1], x, true);
    const int pool1 = x = pool(x);
    x = conv(stream, L[2], x, true);
    const int pool2 = x = pool(x);
    x = conv(stream, L[3], x, true);
    const int pool3 = x = pool(x);
    x = conv(stream, L[4], x, true);
    x = pool(x);
    x = conv(stream, L[5], x, true);
    x = conv(stream, L[6], x, true);
    x = conv(stream, L[7], concat(upsample(x), pool3), true);
    x = conv(stream, L[8], x, true);
    x = conv(stream, L[9], concat(upsample(x), pool2), true);
    x = conv(stream, L[10], x, true);
    x = conv(stream, L[11], concat(upsample(x), pool1), true);
    x = conv(stream, L[12], x, true);
    x = conv(stream, L[13], concat(upsample(x), input), true);
    x = conv(stream, L[14], x, true);
    x = conv(stream, L[15], x, false);
    output_ = reorder(x, memory::desc({1, 3, height, width}, Type::f32, Tag::nhwc));
    stream.wait();
  }

  // Runs on `input` (height x width x input channels, interleaved) into `output` (x 3).
  void run(float* input, float* output) const {
    dnnl::stream stream(engine_);
    std::vector<memory> tensors;
    for (std::size_t t = 0; t < descs_.size(); ++t)
      tensors.push_back(t == 0              ? memory(descs_[t], engine_, input)
                        : int(t) == output_ ? memory(descs_[t], engine_, output)
                                            : memory(descs_[t], engine_));
    for (const Operation& op : operations_) {
      std::unordered_map<int, memory> args = op.fixed;
      for (const auto& [arg, tensor] : op.tensors) args[arg] = tensors[std::size_t(tensor)];
      args[DNNL_ARG_SCRATCHPAD] = memory(op.scratchpad, engine_);
      op.primitive.execute(stream, args);
    }
    stream.wait();
  }

 private:
  // Scratchpads are the caller's (each tile its own), so that tiles may run at once: with the
  // library's, a primitive is not safe to run from two threads.
  struct Operation {
    dnnl::primitive primitive;
    std::vector<std::pair<int, int>> tensors;  // (argument, tensor)
    std::unordered_map<int, memory> fixed;     // weights, bias
    memory::desc scratchpad;
  };
  static dnnl::primitive_attr user_scratchpad() {
    dnnl::primitive_attr attr;
    attr.set_scratchpad_mode(dnnl::scratchpad_mode::user);
    return attr;
  }

  int add(const memory::dims& dims, Tag tag) { return add(memory::desc(dims, Type::f32, tag)); }
  int add(const memory::desc& desc) {
    descs_.push_back(desc);
    return int(descs_.size()) - 1;
  }
  const memory::desc& desc(int t) const { return descs_[std::size_t(t)]; }
  memory::dims dims(int t) const { return desc(t).dims(); }

  int reorder(int t, const memory::desc& wanted) {
    if (desc(t) == wanted) return t;
    const int out = add(wanted);
    operations_.push_back(
        {dnnl::reorder(dnnl::reorder::primitive_desc(engine_, desc(t), engine_, wanted)),
         {{DNNL_ARG_FROM, t}, {DNNL_ARG_TO, out}},
         {},
         {}});
    return out;
  }

  int conv(dnnl::stream& stream, const UNetLayer& layer, int t, bool relu) {
    const memory::dim H = dims(t)[2], W = dims(t)[3];
    const memory::desc src({1, layer.in_channels, H, W}, Type::f32, Tag::any),
        weights({layer.out_channels, layer.in_channels, 3, 3}, Type::f32, Tag::any),
        bias({layer.out_channels}, Type::f32, Tag::a),
        dst({1, layer.out_channels, H, W}, Type::f32, Tag::any);
    const dnnl::convolution_forward::desc d(dnnl::prop_kind::forward_inference,
                                            dnnl::algorithm::convolution_direct, src, weights, bias,
                                            dst, {1, 1}, {1, 1}, {1, 1});
    dnnl::primitive_attr attr = user_scratchpad();
    if (relu) {
      dnnl::post_ops post;
      post.append_eltwise(1.f, dnnl::algorithm::eltwise_relu, 0.f, 0.f);
      attr.set_post_ops(post);
    }
    const dnnl::convolution_forward::primitive_desc pd(d, attr, engine_);
    const int in = reorder(t, pd.src_desc());
    // the weights once, in the layout the primitive wants
    memory user_weights({{layer.out_channels, layer.in_channels, 3, 3}, Type::f32, Tag::oihw},
                        engine_, const_cast<float*>(layer.weights.data()));
    memory w(pd.weights_desc(), engine_);
    dnnl::reorder(user_weights, w).execute(stream, user_weights, w);
    memory b(bias, engine_);
    std::copy(layer.bias.begin(), layer.bias.end(), static_cast<float*>(b.get_data_handle()));
    const int out = add(pd.dst_desc());
    operations_.push_back({dnnl::convolution_forward(pd),
                           {{DNNL_ARG_SRC, in}, {DNNL_ARG_DST, out}},
                           {{DNNL_ARG_WEIGHTS, w}, {DNNL_ARG_BIAS, b}},
                           pd.scratchpad_desc()});
    return out;
  }

  int pool(int t) {
    memory::dims half = dims(t);
    half[2] /= 2, half[3] /= 2;
    const dnnl::pooling_forward::desc d(
        dnnl::prop_kind::forward_inference, dnnl::algorithm::pooling_max, desc(t),
        memory::desc(half, Type::f32, Tag::any), {2, 2}, {2, 2}, {0, 0}, {0, 0});
    const dnnl::pooling_forward::primitive_desc pd(d, user_scratchpad(), engine_);
    const int out = add(pd.dst_desc());
    operations_.push_back({dnnl::pooling_forward(pd),
                           {{DNNL_ARG_SRC, t}, {DNNL_ARG_DST, out}},
                           {},
                           pd.scratchpad_desc()});
    return out;
  }

  int upsample(int t) {
    memory::dims twice = dims(t);
    twice[2] *= 2, twice[3] *= 2;
    const dnnl::resampling_forward::desc d(dnnl::prop_kind::forward_inference,
                                           dnnl::algorithm::resampling_nearest, desc(t),
                                           memory::desc(twice, Type::f32, Tag::any));
    const dnnl::resampling_forward::primitive_desc pd(d, user_scratchpad(), engine_);
    const int out = add(pd.dst_desc());
    operations_.push_back({dnnl::resampling_forward(pd),
                           {{DNNL_ARG_SRC, t}, {DNNL_ARG_DST, out}},
                           {},
                           pd.scratchpad_desc()});
    return out;
  }

  int concat(int a, int b) {
    const dnnl::concat::primitive_desc pd(1, {desc(a), desc(b)}, engine_);
    const int out = add(pd.dst_desc());
    operations_.push_back(
        {dnnl::concat(pd),
         {{DNNL_ARG_MULTIPLE_SRC, a}, {DNNL_ARG_MULTIPLE_SRC + 1, b}, {DNNL_ARG_DST, out}},
         {},
         {}});
    return out;
  }

  dnnl::engine engine_;
  std::vector<memory::desc> descs_;
  std::vector<Operation> operations_;
  int output_ = -1;
};

int round_up(int x, int to) { return (x + to - 1) / to * to; }

// The tiles of one image dimension: cores that partition it, each inside an input window that
// lies inside the image (so the image's own edges are the network's, as untiled) with at least
// kOverlap of context where the image goes on; one window of the whole (aligned, zero-padded)
// dimension when it fits.
struct TileAxis {
  struct Tile {
    int core_begin, core_end, input_begin;
  };
  std::vector<Tile> tiles;
  int input;  // every window's size
};
TileAxis tile_axis(int size) {
  if (size <= kTile) return {{{0, size, 0}}, round_up(size, kAlignment)};
  TileAxis axis{{}, kTile};
  for (int begin = 0; begin < size; begin += kTileCore)
    axis.tiles.push_back(
        {begin, std::min(begin + kTileCore, size), std::clamp(begin - kOverlap, 0, size - kTile)});
  return axis;
}

}  // namespace

struct UNet::Impl {
  UNetWeights weights;
  dnnl::engine engine{dnnl::engine::kind::cpu, 0};
  std::mutex mutex;
  // by tile size and thread: oneDNN's primitives give wrong sums when two threads run one at once
  std::map<std::tuple<int, int, int>, std::shared_ptr<const Network>> networks;

  std::shared_ptr<const Network> network(int height, int width) {
    const int thread = tbb::this_task_arena::current_thread_index();
    std::lock_guard<std::mutex> lock(mutex);
    auto& net = networks[{height, width, thread}];
    if (!net) net = std::make_shared<const Network>(engine, weights, height, width);
    return net;
  }
};

UNet::UNet(UNetWeights weights) : impl_(std::make_unique<Impl>()) {
  impl_->weights = std::move(weights);
}
UNet::~UNet() = default;
UNet::UNet(UNet&&) noexcept = default;

int UNet::input_channels() const { return impl_->weights.layers.front().in_channels; }

Image<float> UNet::run(const Image<float>& input) const {
  const int C = input_channels(), W = input.width, H = input.height;
  if (input.channels != C)
    throw std::invalid_argument("the U-Net takes " + std::to_string(C) + " channels, not " +
                                std::to_string(input.channels));
  const TileAxis ax = tile_axis(W), ay = tile_axis(H);
  Image<float> out(W, H, 3);
  const std::size_t tiles = ax.tiles.size() * ay.tiles.size();
  tbb::parallel_for(std::size_t(0), tiles, [&](std::size_t k) {
    const TileAxis::Tile &tx = ax.tiles[k % ax.tiles.size()], &ty = ay.tiles[k / ax.tiles.size()];
    std::vector<float> tile(std::size_t(ax.input) * ay.input * C, 0.f),
        result(std::size_t(ax.input) * ay.input * 3);
    for (int y = 0; y < std::min(ay.input, H - ty.input_begin); ++y)
      std::copy_n(input.pixel(tx.input_begin, ty.input_begin + y),
                  std::size_t(std::min(ax.input, W - tx.input_begin)) * C,
                  &tile[std::size_t(y) * ax.input * C]);
    omp_set_num_threads(1);  // one tile, one thread: the same sums whatever the thread count
    impl_->network(ay.input, ax.input)->run(tile.data(), result.data());
    for (int y = ty.core_begin; y < ty.core_end; ++y)
      std::copy_n(
          &result[(std::size_t(y - ty.input_begin) * ax.input + (tx.core_begin - tx.input_begin)) *
                  3],
          std::size_t(tx.core_end - tx.core_begin) * 3, out.pixel(tx.core_begin, y));
  });
  return out;
}

}  // namespace flowscape
