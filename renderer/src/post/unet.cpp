// OIDN's U-Net weights from a Tensor Archive (training/tza.py's format); the forward pass is
// unet_onednn.cpp (FLOWSCAPE_DENOISER=ON) or unet_absent.cpp.
#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>

#include "flowscape/core/files.h"
#include "flowscape/renderer/neural_denoise.h"

namespace flowscape {
namespace fs = std::filesystem;

const std::vector<std::string> kUNetLayers{"enc_conv0",  "enc_conv1",  "enc_conv2",  "enc_conv3",
                                           "enc_conv4",  "enc_conv5a", "enc_conv5b", "dec_conv4a",
                                           "dec_conv4b", "dec_conv3a", "dec_conv3b", "dec_conv2a",
                                           "dec_conv2b", "dec_conv1a", "dec_conv1b", "dec_conv0"};

namespace {

// ---- the Tensor Archive ---------------------------------------------------------------------

constexpr std::uint16_t kTzaMagic = 0x41D7;

// Reads little-endian fields of a byte string, each checked to lie inside it.
class Bytes {
 public:
  Bytes(const std::string& data, const fs::path& path) : data_(data), path_(path) {}
  template <class T>
  T read() {
    T value;
    need(sizeof(T));
    std::memcpy(&value, data_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }
  std::string text(std::size_t n) {
    need(n);
    at_ += n;
    return data_.substr(at_ - n, n);
  }
  void seek(std::uint64_t at) {
    if (at > data_.size()) fail("table offset beyond the end of the file");
    at_ = std::size_t(at);
  }
  const char* at(std::uint64_t offset, std::uint64_t bytes) const {
    if (offset > data_.size() || bytes > data_.size() - offset)
      fail("a tensor's data lies beyond the end of the file");
    return data_.data() + offset;
  }
  [[noreturn]] void fail(const std::string& what) const {
    throw FileError(path_, "not an OIDN weights file (.tza): " + what);
  }

 private:
  void need(std::size_t n) const {
    if (at_ + n > data_.size()) fail("truncated");
  }
  const std::string& data_;
  fs::path path_;
  std::size_t at_ = 0;
};

float half_to_float(std::uint16_t h) {
  const std::uint32_t sign = std::uint32_t(h >> 15) << 31, exponent = (h >> 10) & 31,
                      mantissa = h & 1023;
  std::uint32_t bits;
  if (exponent == 31) {
    bits = sign | 0x7F800000u | (mantissa << 13);  // inf, nan
  } else if (exponent != 0) {
    bits = sign | ((exponent + 112) << 23) | (mantissa << 13);
  } else {  // zero and subnormals: mantissa x 2^-24
    const float value = float(mantissa) * 5.9604644775390625e-8f;
    std::memcpy(&bits, &value, 4);
    bits |= sign;
  }
  float out;
  std::memcpy(&out, &bits, 4);
  return out;
}

struct Tensor {
  std::vector<std::uint32_t> shape;
  std::string layout;
  char type;
  std::uint64_t offset;
};

std::vector<float> tensor_values(const Bytes& bytes, const Tensor& t, std::size_t count) {
  const std::size_t size = t.type == 'h' ? 2 : 4;
  const char* data = bytes.at(t.offset, std::uint64_t(count) * size);
  std::vector<float> values(count);
  for (std::size_t i = 0; i < count; ++i) {
    if (t.type == 'h') {
      std::uint16_t h;
      std::memcpy(&h, data + 2 * i, 2);
      values[i] = half_to_float(h);
    } else {
      std::memcpy(&values[i], data + 4 * i, 4);
    }
  }
  return values;
}

}  // namespace

UNetWeights read_unet_weights(const fs::path& path) {
  const std::string data = read_file(path, std::uintmax_t(1) << 30);
  Bytes bytes(data, path);
  if (bytes.read<std::uint16_t>() != kTzaMagic) bytes.fail("wrong magic number");
  if (bytes.read<std::uint8_t>() != 2) bytes.fail("unsupported version");
  bytes.read<std::uint8_t>();
  bytes.seek(bytes.read<std::uint64_t>());
  const std::uint32_t count = bytes.read<std::uint32_t>();
  if (count > 4096) bytes.fail("too many tensors");
  std::map<std::string, Tensor> table;
  for (std::uint32_t k = 0; k < count; ++k) {
    const std::string name = bytes.text(bytes.read<std::uint16_t>());
    Tensor t;
    const std::uint8_t dims = bytes.read<std::uint8_t>();
    if (dims > 8) bytes.fail("tensor \"" + name + "\" has too many dimensions");
    for (int d = 0; d < dims; ++d) t.shape.push_back(bytes.read<std::uint32_t>());
    t.layout = bytes.text(dims);
    t.type = bytes.text(1)[0];
    t.offset = bytes.read<std::uint64_t>();
    if (t.type != 'h' && t.type != 'f') bytes.fail("tensor \"" + name + "\" is not float");
    table[name] = t;
  }
  UNetWeights weights;
  for (const std::string& name : kUNetLayers) {
    const auto w = table.find(name + ".weight"), b = table.find(name + ".bias");
    if (w == table.end() || b == table.end()) bytes.fail("no layer \"" + name + "\"");
    const std::vector<std::uint32_t>& s = w->second.shape;
    if (w->second.layout != "oihw" || s.size() != 4 || s[2] != 3 || s[3] != 3 || s[0] == 0 ||
        s[0] > 4096 || s[1] == 0 || s[1] > 4096 ||
        b->second.shape != std::vector<std::uint32_t>{s[0]})
      bytes.fail("layer \"" + name + "\" is not a 3x3 convolution with a bias");
    UNetLayer layer{name, int(s[0]), int(s[1]), {}, {}};
    layer.weights = tensor_values(bytes, w->second, std::size_t(s[0]) * s[1] * 9);
    layer.bias = tensor_values(bytes, b->second, s[0]);
    weights.layers.push_back(std::move(layer));
  }
  // the channels must chain as the forward pass concatenates them
  const auto& L = weights.layers;
  const auto out = [&](int i) { return L[std::size_t(i)].out_channels; };
  const auto in = [&](int i) { return L[std::size_t(i)].in_channels; };
  const bool chained =
      in(1) == out(0) && in(2) == out(1) && in(3) == out(2) && in(4) == out(3) && in(5) == out(4) &&
      in(6) == out(5) && in(7) == out(6) + out(3) && in(8) == out(7) && in(9) == out(8) + out(2) &&
      in(10) == out(9) && in(11) == out(10) + out(1) && in(12) == out(11) &&
      in(13) == out(12) + in(0) && in(14) == out(13) && in(15) == out(14) && out(15) == 3;
  if (!chained) bytes.fail("its layers' channels do not make OIDN's U-Net");
  return weights;
}

}  // namespace flowscape
