// The offscreen context and its full-screen pass (include/specula/gl/context.h): what the driver
// reports, every pixel where it belongs for any tiling, compile and link errors on one line.
#include "specula/gl/context.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <iostream>
#include <memory>

#include "gl_support.h"

namespace specula::gl {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using specula::testing::shared_context;

// A full-screen triangle from gl_VertexID, like render::scene_vertex_shader's.
constexpr const char* kVertex = R"(#version 330 core
void main() {
  vec2 corner = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
  gl_Position = vec4(2.0 * corner - 1.0, 0.0, 1.0);
}
)";

// Each pixel's own coordinates in the whole image (bottom-up), and a constant.
constexpr const char* kCoordinates = R"(#version 330 core
uniform vec2 u_pixel_offset;
out vec4 colour;
void main() { colour = vec4(gl_FragCoord.xy + u_pixel_offset, 0.25, 1.0); }
)";

TEST(Context, ReportsAnOpenGl33OrNewerRenderer) {
  const ContextInfo& info = shared_context().info();
  std::cout << "[ context  ] " << to_string(info) << ", max texture " << info.max_texture_size << ", max viewport "
            << info.max_viewport_width << "x" << info.max_viewport_height << '\n';
  EXPECT_FALSE(info.renderer.empty());
  EXPECT_FALSE(info.vendor.empty());
  int major = 0, minor = 0;
  ASSERT_EQ(std::sscanf(info.version.c_str(), "%d.%d", &major, &minor), 2) << info.version;
  EXPECT_GE(major * 10 + minor, 33) << info.version;
  EXPECT_GE(info.max_texture_size, 1024);
  EXPECT_GE(default_tile_side(info), 1024);
  EXPECT_THAT(to_string(info), HasSubstr(info.platform));
}

// Every pixel of a width × height image drawn in tiles of `tile` pixels.
void expect_pixel_coordinates(int width, int height, int tile) {
  const Program program(shared_context(), kVertex, kCoordinates);
  const render::Image image = draw_full_screen(program, width, height, tile);
  ASSERT_EQ(image.width(), width);
  ASSERT_EQ(image.height(), height);
  int wrong = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const render::Rgb expected{x + 0.5, height - 1 - y + 0.5, 0.25};  // row 0 on top: the flip
      if (image.at(x, y) != expected && ++wrong <= 5)
        ADD_FAILURE() << "pixel " << x << "," << y << " of " << width << "x" << height << " in tiles of " << tile
                      << ": " << image.at(x, y).r << "," << image.at(x, y).g << "," << image.at(x, y).b;
    }
  EXPECT_EQ(wrong, 0);
}

TEST(FullScreenPass, PutsEveryPixelAtItsPlaceTopRowFirst) { expect_pixel_coordinates(37, 23, 4096); }

TEST(FullScreenPass, StitchesTilesOfAnySize) {
  expect_pixel_coordinates(37, 23, 8);   // partial tiles on the right and at the top
  expect_pixel_coordinates(37, 23, 1);
  expect_pixel_coordinates(64, 64, 32);  // exact tiles
  expect_pixel_coordinates(1, 1, 2048);
}

TEST(FullScreenPass, DrawsImagesWiderThanOneTile) {
  const ContextInfo& info = shared_context().info();
  expect_pixel_coordinates(default_tile_side(info) + 5, 3, default_tile_side(info));
}

TEST(FullScreenPass, RefusesBadSizes) {
  const Program program(shared_context(), kVertex, kCoordinates);
  EXPECT_THROW(draw_full_screen(program, 0, 10, 64), InvalidArgument);
  EXPECT_THROW(draw_full_screen(program, 10, render::kMaxImageSide + 1, 64), InvalidArgument);
  EXPECT_THROW(draw_full_screen(program, 10, 10, 0), InvalidArgument);
}

std::string error_of(const char* vertex, const char* fragment) {
  try {
    const Program program(shared_context(), vertex, fragment);
  } catch (const GlError& e) {
    return e.what();
  }
  return "no error";
}

TEST(Program, ACompileErrorNamesTheStageAndGivesTheLogOnOneLine) {
  const std::string error = error_of(kVertex, "#version 330 core\nout vec4 c;\nvoid main() { c = vec4(undeclared_name); }\n");
  EXPECT_THAT(error, HasSubstr("fragment shader does not compile"));
  EXPECT_THAT(error, HasSubstr("undeclared_name"));
  EXPECT_THAT(error, Not(HasSubstr("\n")));
  EXPECT_THAT(error_of("#version 330 core\nvoid main() { gl_Position = 1; }\n", kCoordinates),
              HasSubstr("vertex shader does not compile"));
}

TEST(Program, ALinkErrorSaysSo) {
  // Declared, called, never defined: each stage compiles, the program does not link.
  const std::string error = error_of(kVertex, "#version 330 core\nfloat never_defined();\nout vec4 c;\n"
                                              "void main() { c = vec4(never_defined()); }\n");
  EXPECT_THAT(error, HasSubstr("does not link"));
  EXPECT_THAT(error, Not(HasSubstr("\n")));
}

// SPECULA_EGL_PLATFORM set for the scope of one test.
class PlatformOverride {
 public:
  explicit PlatformOverride(const char* value) { ::setenv("SPECULA_EGL_PLATFORM", value, 1); }
  ~PlatformOverride() { ::unsetenv("SPECULA_EGL_PLATFORM"); }
};

std::string context_error() {
  try {
    const Context context;
    return "made on " + context.info().platform;
  } catch (const GlError& e) {
    return e.what();
  }
}

TEST(Context, TheEnvironmentCanChooseThePlatform) {
  {
    const PlatformOverride surfaceless("surfaceless");
    EXPECT_EQ(context_error(), "made on Mesa surfaceless");
  }
  {
    // A GPU machine makes it on its device; this one (llvmpipe only) says that it has none.
    const PlatformOverride device("device");
    const std::string outcome = context_error();
    EXPECT_TRUE(outcome.starts_with("made on EGL device") ||
                outcome == "OpenGL is not available: EGL lists no device but Mesa's software one (SPECULA_EGL_PLATFORM=device)")
        << outcome;
  }
  {
    const PlatformOverride unknown("vulkan");
    EXPECT_EQ(context_error(), "SPECULA_EGL_PLATFORM 'vulkan' is unknown: expected device or surfaceless");
  }
  shared_context().make_current();
}

TEST(Context, TwoContextsLiveSideBySideAndOutliveEachOther) {
  auto first = std::make_unique<Context>();
  const Context second;
  first.reset();  // must not end the display the second one uses
  const Program program(second, kVertex, kCoordinates);
  EXPECT_EQ(draw_full_screen(program, 2, 2, 64).at(1, 0), (render::Rgb{1.5, 1.5, 0.25}));
  shared_context().make_current();
}

}  // namespace
}  // namespace specula::gl
