#include "flowscape/formats/image_io.h"

#include <OpenImageIO/imageio.h>
#include <fcntl.h>
#include <unistd.h>

#include <mutex>

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

std::unique_ptr<OIIO::ImageInput> open_input(const std::filesystem::path& path) {
  if (!std::filesystem::exists(path)) throw FileError(path, "file not found");
  MutedLibraryStderr muted;
  auto in = OIIO::ImageInput::open(path.string());
  if (!in) throw FileError(path, "cannot read image: " + first_line(OIIO::geterror()));
  const OIIO::ImageSpec& spec = in->spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw FileError(path, "image has no pixels");
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
void write_image(const std::filesystem::path& path, ImageView<const T> image,
                 const std::vector<std::string>& channel_names) {
  write_atomically(path, [&](const std::filesystem::path& temporary) {
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out)
      throw FileError(path, "no image writer for this extension: " + first_line(OIIO::geterror()));
    OIIO::ImageSpec spec(image.width, image.height, image.channels, type_of<T>());
    if (!channel_names.empty()) spec.channelnames = channel_names;
    // OpenEXR output stamps the write time otherwise; a release must be the same bytes every run
    spec.attribute("DateTime", "");
    if (!out->open(temporary.string(), spec) || !out->write_image(type_of<T>(), image.data) ||
        !out->close())
      throw FileError(path, "cannot write image: " + first_line(out->geterror()));
  });
}

template Image<std::uint8_t> read_image(const std::filesystem::path&);
template Image<std::uint16_t> read_image(const std::filesystem::path&);
template Image<float> read_image(const std::filesystem::path&);
template void write_image(const std::filesystem::path&, ImageView<const std::uint8_t>,
                          const std::vector<std::string>&);
template void write_image(const std::filesystem::path&, ImageView<const std::uint16_t>,
                          const std::vector<std::string>&);
template void write_image(const std::filesystem::path&, ImageView<const float>,
                          const std::vector<std::string>&);

}  // namespace flowscape
