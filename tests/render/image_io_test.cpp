// Image files (include/specula/render/image_io.h): PNG and EXR round trips with their metadata,
// atomic writes, and one-line errors for bad paths and files.
#include "specula/render/image_io.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <cmath>
#include <random>

#include "render_support.h"
#include "specula/exceptions.h"
#include "specula/io/files.h"
#include "text_support.h"

namespace specula::render {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;
using ::testing::Pair;
using specula::testing::TempDir;

// HDR content: values from 0 to 4 in every channel, with exact zeros and ones.
Image sample_image(int width, int height) {
  Image image(width, height);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> value(0, 4);
  for (float& s : image.samples()) s = static_cast<float>(value(random));
  image.set(0, 0, {0, 1, 0.5});
  return image;
}

const Metadata kMetadata{{"model", "log-normalized"}, {"parameters", "n=50"}, {"form", "rv"},
                         {"lights", "dir:-1,1,1:1,1,1:1 point:0,0,4:1,0.9,0.8:25"}};

std::string get(const Metadata& metadata, const std::string& key) {
  for (const auto& [k, v] : metadata)
    if (k == key) return v;
  return "<missing " + key + ">";
}

TEST(Exr, FloatRoundTripIsExactWithItsMetadata) {
  TempDir dir;
  const Image image = sample_image(37, 23);
  write_exr(dir / "a.exr", image, ExrPixel::float32, kMetadata);
  const ImageFile read = read_exr(dir / "a.exr");
  ASSERT_EQ(read.image.width(), 37);
  ASSERT_EQ(read.image.height(), 23);
  EXPECT_TRUE(std::ranges::equal(read.image.samples(), image.samples()));
  for (const auto& [key, value] : kMetadata) EXPECT_EQ(get(read.metadata, key), value);
  EXPECT_THAT(dir.listing(), ElementsAre("a.exr"));
}

/// The line offset table of a scanline EXR file: the file offset of each chunk, after the header
/// (magic, version, attributes name\0 type\0 size value, then \0).
std::vector<std::uint64_t> line_offsets(const std::string& bytes, std::size_t chunks) {
  std::size_t at = 8;
  while (bytes.at(at) != '\0') {
    const std::size_t type_end = bytes.find('\0', bytes.find('\0', at) + 1);
    std::int32_t size = 0;
    std::memcpy(&size, bytes.data() + type_end + 1, 4);
    at = type_end + 5 + static_cast<std::size_t>(size);
  }
  std::vector<std::uint64_t> offsets(chunks);
  std::memcpy(offsets.data(), bytes.data() + at + 1, 8 * chunks);
  return offsets;
}

TEST(Exr, TheLineOffsetTableIsWritten) {
  // The table is filled in when OpenEXR closes the file: bytes taken before that have zeros
  // there, which readers can only work around by scanning the whole file.
  TempDir dir;
  write_exr(dir / "a.exr", sample_image(37, 40), ExrPixel::float32, kMetadata);
  const std::string bytes = io::read_file(dir / "a.exr");
  const auto offsets = line_offsets(bytes, 3);  // ZIP: 16 lines a chunk
  for (std::size_t i = 0; i < offsets.size(); ++i) {
    ASSERT_GT(offsets[i], 0u) << i;
    ASSERT_LT(offsets[i] + 8, bytes.size()) << i;
    std::int32_t y = -1;
    std::memcpy(&y, bytes.data() + offsets[i], 4);
    EXPECT_EQ(y, static_cast<std::int32_t>(16 * i)) << "chunk " << i << " starts elsewhere";
  }
  std::string broken = bytes;  // the control: a zeroed table fails the check
  const std::size_t table = static_cast<std::size_t>(offsets[0]) - 24;
  std::fill_n(broken.begin() + static_cast<std::ptrdiff_t>(table), 24, '\0');
  EXPECT_EQ(line_offsets(broken, 3)[0], 0u);
}

TEST(Exr, HalfRoundTripKeepsElevenSignificantBits) {
  TempDir dir;
  const Image image = sample_image(16, 9);
  write_exr(dir / "a.exr", image);
  const ImageFile read = read_image(dir / "a.exr");
  for (std::size_t i = 0; i < image.samples().size(); ++i)
    EXPECT_NEAR(read.image.samples()[i], image.samples()[i], image.samples()[i] * 0x1p-11) << i;
  EXPECT_EQ(read.image.at(0, 0), (Rgb{0, 1, 0.5}));
}

TEST(Png, RoundTripIsWithinHalfACodeAfterSrgbEncoding) {
  TempDir dir;
  Image image = sample_image(41, 17);
  for (float& s : image.samples()) s /= 4;  // in [0, 1]: no clamping
  write_png(dir / "a.png", image, {}, kMetadata);
  const ImageFile read = read_png(dir / "a.png");
  ASSERT_EQ(read.image.width(), 41);
  ASSERT_EQ(read.image.height(), 17);
  for (std::size_t i = 0; i < image.samples().size(); ++i)
    EXPECT_LE(std::abs(255 * srgb_encode(read.image.samples()[i]) - 255 * srgb_encode(image.samples()[i])), 0.5 + 1e-4) << i;
  EXPECT_THAT(read.metadata, ElementsAre(Pair("model", "log-normalized"), Pair("parameters", "n=50"),
                                         Pair("form", "rv"), Pair("lights", get(kMetadata, "lights"))));
}

TEST(Png, StoresTheDisplayTransformedCodes) {
  TempDir dir;
  const Image image = sample_image(8, 8);
  const Display display{-1.5, ToneMap::aces};
  write_png(dir / "a.png", image, display);
  const ImageFile read = read_png(dir / "a.png");
  const auto codes = to_srgb8(image, display);
  for (std::size_t i = 0; i < codes.size(); ++i)
    EXPECT_EQ(std::lround(255 * srgb_encode(read.image.samples()[i])), codes[i]) << i;
  EXPECT_THAT(read.metadata, IsEmpty());
}

TEST(Png, StoresAnSrgb8ImageCodeForCodeWithItsMetadata) {
  TempDir dir;
  Srgb8Image image(7, 5, {10, 200, 30});
  image.set(6, 4, {255, 0, 128});
  image.set(0, 0, {0, 1, 2});
  write_png(dir / "a.png", image, kMetadata);
  const ImageFile read = read_png(dir / "a.png");
  ASSERT_EQ(read.image.width(), 7);
  ASSERT_EQ(read.image.height(), 5);
  const auto code = [&](int x, int y) {
    const Rgb v = read.image.at(x, y);
    const auto c = [](double linear) { return std::lround(255 * srgb_encode(linear)); };
    return std::array<long, 3>{c(v.r), c(v.g), c(v.b)};
  };
  EXPECT_EQ(code(6, 4), (std::array<long, 3>{255, 0, 128}));
  EXPECT_EQ(code(0, 0), (std::array<long, 3>{0, 1, 2}));
  EXPECT_EQ(code(3, 2), (std::array<long, 3>{10, 200, 30}));
  EXPECT_EQ(get(read.metadata, "lights"), get(kMetadata, "lights"));
  EXPECT_THROW(write_png(dir / "missing/a.png", image), InvalidArgument);
  EXPECT_THAT(dir.listing(), ElementsAre("a.png"));
}

TEST(Png, KeepsNonAsciiValuesAsInternationalText) {
  TempDir dir;
  write_png(dir / "a.png", sample_image(2, 2), {}, {{"scene", "/tmp/сфера.obj"}});
  EXPECT_THAT(read_png(dir / "a.png").metadata, ElementsAre(Pair("scene", "/tmp/сфера.obj")));
}

TEST(ImageFiles, OverwriteAtomically) {
  TempDir dir;
  write_png(dir / "a.png", sample_image(4, 4), {});
  write_png(dir / "a.png", sample_image(5, 3), {});
  EXPECT_EQ(read_png(dir / "a.png").image.width(), 5);
  EXPECT_THAT(dir.listing(), ElementsAre("a.png"));
}

TEST(ImageFiles, UnwritablePathsFailInOneLineAndLeaveNoFile) {
  TempDir dir;
  const Image image = sample_image(4, 4);
  for (const auto& path : {dir / "missing/a.png", dir / "missing/a.exr"}) {
    try {
      if (image_format(path) == ImageFormat::png) write_png(path, image, {});
      else write_exr(path, image);
      ADD_FAILURE() << path << " written";
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr("cannot write '" + path.string() + "'"));
      EXPECT_THAT(std::string(e.what()), ::testing::Not(HasSubstr("\n")));
    }
  }
  EXPECT_THAT(dir.listing(), IsEmpty());
}

TEST(ImageFiles, FormatComesFromTheExtensionInAnyCase) {
  EXPECT_EQ(image_format("a/b.PNG"), ImageFormat::png);
  EXPECT_EQ(image_format("b.exr"), ImageFormat::exr);
  for (const char* path : {"b.jpg", "b", "png", "b.png.tmp"})
    EXPECT_THROW(image_format(path), InvalidArgument) << path;
  EXPECT_THROW(read_image("b.tiff"), InvalidArgument);
}

TEST(ImageFiles, ReadingBadFilesFailsInOneLineNamingThePath) {
  TempDir dir;
  const Image image = sample_image(6, 6);
  write_png(dir / "good.png", image, {});
  const std::string png = specula::testing::read_file(dir / "good.png");
  const auto expect_error = [&](const std::filesystem::path& path, const std::string& what) {
    try {
      read_image(path);
      ADD_FAILURE() << path << " read";
    } catch (const InvalidArgument& e) {
      EXPECT_THAT(e.what(), HasSubstr("cannot read '" + path.string() + "': " + what));
    }
  };
  expect_error(dir / "missing.png", "No such file");
  expect_error(dir / "missing.exr", "");
  expect_error(dir.write("text.png", "not an image"), "not a PNG file");
  expect_error(dir.write("cut.png", png.substr(0, png.size() / 2)), "");
  expect_error(dir.write("text.exr", "not an image"), "");
  std::filesystem::create_directory(dir / "folder.png");
  expect_error(dir / "folder.png", "it is a directory");
}

}  // namespace
}  // namespace specula::render
