#include "flowscape/formats/image_io.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <cstring>
#include <fstream>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

namespace flowscape {

namespace {

// Points fd 2 at /dev/null while at least one instance lives (decodes may run in parallel).
class MutedLibraryStderr {
 public:
  MutedLibraryStderr() {
    diagnostics();  // duplicate the real stderr before the first mute
    std::lock_guard lock(mutex_);
    if (depth_++ > 0) return;
    std::fflush(stderr);
    saved_ = dup(STDERR_FILENO);
    const int null_fd = open("/dev/null", O_WRONLY);
    if (null_fd >= 0) dup2(null_fd, STDERR_FILENO), close(null_fd);
  }
  ~MutedLibraryStderr() {
    std::lock_guard lock(mutex_);
    if (--depth_ > 0 || saved_ < 0) return;
    std::fflush(stderr);
    dup2(saved_, STDERR_FILENO);
    close(saved_);
    saved_ = -1;
  }
  MutedLibraryStderr(const MutedLibraryStderr&) = delete;
  MutedLibraryStderr& operator=(const MutedLibraryStderr&) = delete;

 private:
  static inline std::mutex mutex_;
  static inline int depth_ = 0, saved_ = -1;
};

// OpenImageIO's messages can span lines; the first says what went wrong.
std::string first_line(const std::string& message) { return message.substr(0, message.find('\n')); }

template <class T>
OIIO::TypeDesc type_of() {
  if constexpr (std::is_same_v<T, std::uint8_t>) return OIIO::TypeDesc::UINT8;
  if constexpr (std::is_same_v<T, std::uint16_t>) return OIIO::TypeDesc::UINT16;
  if constexpr (std::is_same_v<T, float>) return OIIO::TypeDesc::FLOAT;
}

std::string describe(OIIO::TypeDesc type) {
  if (type == OIIO::TypeDesc::UINT8) return "8-bit";
  if (type == OIIO::TypeDesc::UINT16) return "16-bit";
  return std::string(type.c_str());
}

// How far a file's pixel data can be compressed: deflate (PNG; EXR zip, zips, and pxr24's 24-bit
// floats) at most 1032:1 (1376:1 for pxr24), run lengths 64:1; EXR's piz (Huffman with runs of
// at most 255 codes) below 500:1, b44 below 11:1. 4096:1 bounds those and dwaa/dwab on any real
// image.
std::uintmax_t max_compression_ratio(const std::string& format, const std::string& compression) {
  if (format == "png") return 1032;
  if (compression == "none" || compression == "rle" || compression == "zip" ||
      compression == "zips" || compression == "pxr24")
    return 1376;
  return 4096;
}

// Rows per compressed chunk of a scanline EXR, by compression (OpenEXR's file layout).
int exr_rows_per_chunk(const std::string& compression) {
  if (compression == "zip" || compression == "pxr24") return 16;
  if (compression == "piz" || compression.starts_with("b44") || compression == "dwaa") return 32;
  if (compression == "dwab") return 256;
  return 1;  // none, rle, zips
}

// Refuses, before anything is allocated, headers that claim more than the file can hold: too many
// pixels or bytes for any image we read, more PNG or EXR data than its compression can hold,
// or more EXR chunks than the file has room for their offsets.
void check_header(const std::filesystem::path& path, const OIIO::ImageInput& in) {
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw FileError(path, "image has no pixels");
  const std::uintmax_t pixels = std::uintmax_t(spec.width) * std::uintmax_t(spec.height);
  const std::uintmax_t bytes = pixels * std::uintmax_t(spec.nchannels) * 4;
  const std::string size = std::to_string(spec.width) + "x" + std::to_string(spec.height) + "x" +
                           std::to_string(spec.nchannels);
  if (pixels > kMaxImagePixels || bytes > kMaxImageBytes)
    throw FileError(path,
                    "header claims " + size + " pixels, over the limit of 2^28 pixels / 2 GiB");
  const std::uintmax_t file_bytes = std::filesystem::file_size(path);
  const std::string format = in.format_name();
  const std::uintmax_t raw = pixels * std::uintmax_t(spec.nchannels) * spec.format.size();
  const std::string compression = spec.get_string_attribute("compression");
  const bool bounded = format == "png" || format == "openexr";
  if (bounded && raw > max_compression_ratio(format, compression) * file_bytes + (1u << 16))
    throw FileError(path, "header claims " + size + " pixels, more than a " +
                              std::to_string(file_bytes) + "-byte " + format + " file can hold");
  if (format == "openexr") {
    const int tile = std::max(spec.tile_width, 1) * std::max(spec.tile_height, 1);
    const std::uintmax_t chunks =
        spec.tile_width > 0 ? pixels / std::uintmax_t(tile)
                            : std::uintmax_t(spec.height) / exr_rows_per_chunk(compression);
    if (chunks * 8 > file_bytes)
      throw FileError(path, "header claims " + size + " pixels, more chunks than a " +
                                std::to_string(file_bytes) + "-byte EXR can hold");
  }
}

// OpenEXR allocates what a header's attributes claim (sizes, line offset tables) while opening, so
// the header is read here first: every attribute must fit in the file, the data window must be
// ordered and within kMaxImagePixels. (OpenEXR's layout: magic, version, then name\0 type\0
// int32 size, value... up to an empty name.)
void check_exr_header(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::string head(std::size_t(std::min<std::uintmax_t>(std::filesystem::file_size(path), 1 << 20)),
                   '\0');
  in.read(head.data(), std::streamsize(head.size()));
  const auto fail = [&](const std::string& problem) {
    throw FileError(path, "EXR header: " + problem);
  };
  std::size_t at = 8;
  const auto text = [&] {
    const std::size_t end = head.find('\0', at);
    if (end == std::string::npos || end - at > 255) fail("truncated or overlong attribute name");
    std::string s = head.substr(at, end - at);
    at = end + 1;
    return s;
  };
  bool has_window = false;
  while (true) {
    const std::string name = text();
    if (name.empty()) break;
    const std::string type = text();
    std::int32_t size = 0;
    if (at + 4 > head.size()) fail("truncated attribute " + name);
    std::memcpy(&size, head.data() + at, 4);
    at += 4;
    if (size < 0 || std::size_t(size) > head.size() - at)
      fail("attribute " + name + " claims " + std::to_string(size) + " bytes, past the file's end");
    if (name == "dataWindow" && type == "box2i" && size == 16) {
      std::int32_t box[4];
      std::memcpy(box, head.data() + at, 16);
      const std::int64_t width = std::int64_t(box[2]) - box[0] + 1,
                         height = std::int64_t(box[3]) - box[1] + 1;
      if (width <= 0 || height <= 0 || std::uintmax_t(width * height) > kMaxImagePixels)
        fail("data window " + std::to_string(width) + "x" + std::to_string(height) +
             " is empty or over the limit of 2^28 pixels");
      has_window = true;
    }
    at += std::size_t(size);
  }
  if (!has_window) fail("no dataWindow");
}

std::unique_ptr<OIIO::ImageInput> open_input(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw FileError(path, "file not found");
  if (!std::filesystem::is_regular_file(path)) throw FileError(path, "not a regular file");
  if (path.extension() == ".exr") check_exr_header(path);
  MutedLibraryStderr muted;
  // the reader of the file's extension only: OpenImageIO would otherwise try every format it knows
  // on a file that fails, slowly and with other formats' messages
  auto in = OIIO::ImageInput::create(path.string());
  if (!in) throw FileError(path, "cannot read image: " + first_line(OIIO::geterror()));
  OIIO::ImageSpec spec;
  if (!in->open(path.string(), spec))
    throw FileError(path, "cannot read image: " + first_line(in->geterror()));
  check_header(path, *in);
  return in;
}

template <class T>
Image<T> read_pixels(OIIO::ImageInput& in, const std::filesystem::path& path) {
  const OIIO::ImageSpec& spec = in.spec();
  Image<T> image(spec.width, spec.height, spec.nchannels);
  MutedLibraryStderr muted;
  if (!in.read_image(0, 0, 0, spec.nchannels, type_of<T>(), image.data.data()))
    throw FileError(path, "corrupt or truncated image: " + first_line(in.geterror()));
  return image;
}

}  // namespace

AnyImage read_any_image(const std::filesystem::path& path) {
  auto in = open_input(path);
  const OIIO::TypeDesc format = in->spec().format;
  if (format == OIIO::TypeDesc::UINT8) return read_pixels<std::uint8_t>(*in, path);
  if (format == OIIO::TypeDesc::UINT16) return read_pixels<std::uint16_t>(*in, path);
  return read_pixels<float>(*in, path);
}

template <class T>
Image<T> read_image(const std::filesystem::path& path) {
  auto in = open_input(path);
  const OIIO::TypeDesc format = in->spec().format;
  const bool float_like = format.basetype == OIIO::TypeDesc::FLOAT ||
                          format.basetype == OIIO::TypeDesc::HALF ||
                          format.basetype == OIIO::TypeDesc::DOUBLE;
  const bool matches = std::is_same_v<T, float> ? float_like : format == type_of<T>();
  if (!matches)
    throw FileError(path,
                    "stores " + describe(format) + " pixels, expected " + describe(type_of<T>()));
  return read_pixels<T>(*in, path);
}

template <class T>
std::vector<unsigned char> encode_image(const std::filesystem::path& path, ImageView<const T> image,
                                        const std::vector<std::string>& channel_names,
                                        const Compression& compression) {
  if (compression.png_level < 0 || compression.png_level > 9)
    throw FileError(
        path, "PNG compression level " + std::to_string(compression.png_level) + " is not in 0..9");
  auto out = OIIO::ImageOutput::create(path.string());
  if (!out)
    throw FileError(path, "no image writer for this extension: " + first_line(OIIO::geterror()));
  OIIO::ImageSpec spec(image.width, image.height, image.channels, type_of<T>());
  if (!channel_names.empty()) spec.channelnames = channel_names;
  // OpenEXR output stamps the write time otherwise; a release must be the same bytes every run
  spec.attribute("DateTime", "");
  spec.attribute("png:compressionLevel", compression.png_level);
  spec.attribute("compression", compression.exr);
  if (compression.exr_half && std::is_same_v<T, float>) spec.set_format(OIIO::TypeDesc::HALF);
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput memory(encoded);
  if (!out->supports("ioproxy") || !out->set_ioproxy(&memory))
    throw FileError(path, "this image type cannot be encoded in memory");
  if (!out->open(path.string(), spec) || !out->write_image(type_of<T>(), image.data) ||
      !out->close())
    throw FileError(path, "cannot encode image: " + first_line(out->geterror()));
  return encoded;
}

template <class T>
void write_image(const std::filesystem::path& path, ImageView<const T> image,
                 const std::vector<std::string>& channel_names, const Compression& compression) {
  // encoded in memory, so that write_file checks every byte that reaches the disk
  const std::vector<unsigned char> encoded = encode_image(path, image, channel_names, compression);
  write_file(path, {reinterpret_cast<const char*>(encoded.data()), encoded.size()});
}

template Image<std::uint8_t> read_image(const std::filesystem::path&);
template Image<std::uint16_t> read_image(const std::filesystem::path&);
template Image<float> read_image(const std::filesystem::path&);
template std::vector<unsigned char> encode_image(const std::filesystem::path&,
                                                 ImageView<const std::uint8_t>,
                                                 const std::vector<std::string>&,
                                                 const Compression&);
template void write_image(const std::filesystem::path&, ImageView<const std::uint8_t>,
                          const std::vector<std::string>&, const Compression&);
template std::vector<unsigned char> encode_image(const std::filesystem::path&,
                                                 ImageView<const std::uint16_t>,
                                                 const std::vector<std::string>&,
                                                 const Compression&);
template void write_image(const std::filesystem::path&, ImageView<const std::uint16_t>,
                          const std::vector<std::string>&, const Compression&);
template std::vector<unsigned char> encode_image(const std::filesystem::path&,
                                                 ImageView<const float>,
                                                 const std::vector<std::string>&,
                                                 const Compression&);
template void write_image(const std::filesystem::path&, ImageView<const float>,
                          const std::vector<std::string>&, const Compression&);

Image<std::uint8_t> jpeg_round_trip(ImageView<const std::uint8_t> rgb, int quality) {
  if (rgb.channels != 3 || quality < 1 || quality > 100)
    throw std::invalid_argument("jpeg_round_trip: an RGB image and a quality in 1..100");
  cv::Mat bgr;
  cv::cvtColor(cv::Mat(rgb.height, rgb.width, CV_8UC3, const_cast<std::uint8_t*>(rgb.data)), bgr,
               cv::COLOR_RGB2BGR);
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", bgr, bytes, {cv::IMWRITE_JPEG_QUALITY, quality});
  cv::Mat decoded = cv::imdecode(bytes, cv::IMREAD_COLOR);
  Image<std::uint8_t> out(rgb.width, rgb.height, 3);
  cv::cvtColor(decoded, cv::Mat(out.height, out.width, CV_8UC3, out.data.data()),
               cv::COLOR_BGR2RGB);
  return out;
}

}  // namespace flowscape
