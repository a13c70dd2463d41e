#pragma once
// Images as files: PNG (8-bit sRGB, libpng) and OpenEXR (linear half or float RGB), each with
// text metadata (model, parameters, form, renderer settings). Writes are atomic: the file is
// encoded in memory, written to a temporary name and renamed, so a failed write leaves no file.
// Every failure is one InvalidArgument line naming the path ("cannot write '…': …").
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "specula/render/image.h"

namespace specula::render {

/// Key-value text: PNG tEXt chunks (keys of 1-79 Latin-1 characters), EXR string attributes.
using Metadata = std::vector<std::pair<std::string, std::string>>;

enum class ExrPixel { half, float32 };
inline constexpr std::size_t kExrPixelCount = static_cast<std::size_t>(ExrPixel::float32) + 1;  // float32: the last

/// "half" or "float" ("" outside the enum).
constexpr const char* to_string(ExrPixel pixel) noexcept {
  switch (pixel) {
    case ExrPixel::half: return "half";
    case ExrPixel::float32: return "float";
  }
  return "";
}
static_assert(names_complete<ExrPixel, kExrPixelCount>([](ExrPixel p) { return to_string(p); }));

/// 8-bit sRGB through `display` (see to_srgb8), one tEXt chunk per metadata entry (iTXt when
/// the value is not ASCII).
void write_png(const std::filesystem::path& path, const Image& image, const Display& display,
               const Metadata& metadata = {});
/// 8-bit sRGB pixels as they are (e.g. a composed comparison panel), with metadata as above.
void write_png(const std::filesystem::path& path, const Srgb8Image& image, const Metadata& metadata = {});

/// 16-bit grayscale samples as they are (no sRGB chunk: data, not a picture), row-major from the
/// top, with metadata as above. Throws InvalidArgument unless gray has width·height samples.
void write_png16(const std::filesystem::path& path, int width, int height, std::span<const std::uint16_t> gray,
                 const Metadata& metadata = {});

/// The linear samples as they are (no display transform), one string attribute per entry.
void write_exr(const std::filesystem::path& path, const Image& image, ExrPixel pixel = ExrPixel::half,
               const Metadata& metadata = {});

enum class ImageFormat { png, exr };

/// By extension, .png or .exr in any case; throws InvalidArgument for any other.
ImageFormat image_format(const std::filesystem::path& path);

struct ImageFile {
  Image image;
  Metadata metadata;  ///< PNG: the tEXt chunks; EXR: the string attributes
};

/// A PNG decoded to linear RGB (sRGB decoding of each 8-bit code; any colour type or bit depth
/// libpng reads, alpha dropped).
ImageFile read_png(const std::filesystem::path& path);
/// An EXR's R, G and B channels (missing ones read as 0) as float.
ImageFile read_exr(const std::filesystem::path& path);
/// read_png or read_exr by extension.
ImageFile read_image(const std::filesystem::path& path);
/// A PNG or OpenEXR file's bytes, told apart by their signatures (an upload's), read as read_png and
/// read_exr read files; `name` stands for the path in the messages. Throws InvalidArgument "cannot
/// read 'name': …" for other bytes or an image of more than `max_pixels` pixels (checked from the
/// header, before any pixel is decoded).
ImageFile decode_image(std::string_view bytes, std::string_view name,
                       std::uint64_t max_pixels = std::uint64_t(kMaxImageSide) * kMaxImageSide);

/// The image as a PNG file's bytes: 8-bit sRGB through `display`, no metadata.
std::string png_bytes(const Image& image, const Display& display);

}  // namespace specula::render
