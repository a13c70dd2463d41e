// The picture commands' scene options (apps/specula/scene_options.h): the command-line syntax of
// lights, tone maps, EXR pixels, sizes and colours, read into the render library's typed values
// with the messages the CLI prints; and SceneOptions, declared once for render and compare.
#include "scene_options.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "specula/catalogue/catalogue.h"
#include "specula/exceptions.h"

namespace specula::cli {
namespace {

using ::testing::HasSubstr;

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InvalidArgument& e) {
    return e.what();
  }
  return "no error";
}

TEST(ParseLight, ReadsDirectionalAndPointLightsWithDefaults) {
  const render::Light d = parse_light("dir:1,2,3");
  EXPECT_EQ(d.kind, render::LightKind::directional);
  EXPECT_EQ(d.direction.z, 3);
  EXPECT_EQ(d.colour, (render::Rgb{1, 1, 1}));
  EXPECT_EQ(d.intensity, 1);
  const render::Light p = parse_light("point:-1,0.5,4:1,0.9,0.8:25");
  EXPECT_EQ(p.kind, render::LightKind::point);
  EXPECT_EQ(p.position.x, -1);
  EXPECT_EQ(p.colour, (render::Rgb{1, 0.9, 0.8}));
  EXPECT_EQ(p.intensity, 25);
  EXPECT_EQ(render::to_string(p), "point:-1,0.5,4:1,0.9,0.8:25");
  EXPECT_EQ(render::to_string(parse_light(render::to_string(d))), render::to_string(d));
}

TEST(ParseLight, RejectsMalformedSpecsNamingThem) {
  for (const char* spec : {"spot:1,2,3", "dir", "dir:1,2", "dir:1,2,3,4", "dir:a,b,c", "dir:0,0,0",
                           "dir:1,2,3:1,1", "dir:1,2,3:1,1,1:-1", "point:1,2,3:1,1,1:1:5", "dir:1,2,nan",
                           "point:1,2,3:-1,1,1", ""}) {
    const std::string error = error_of([&] { parse_light(spec); });
    EXPECT_NE(error, "no error") << "accepted '" << spec << "'";
    EXPECT_THAT(error, HasSubstr(std::string("'") + spec + "'")) << spec;
  }
}

// The messages `specula render --light …` prints after "specula: error: ".
TEST(ParseLight, SaysWhatIsWrongAsTheCliPrintsIt) {
  const auto error = [](const char* spec) { return error_of([&] { parse_light(spec); }); };
  EXPECT_EQ(error("bad"), "malformed light 'bad': expected dir:x,y,z[:r,g,b[:intensity]] or point:x,y,z[:r,g,b[:intensity]]");
  EXPECT_EQ(error("dir:1,2,3:1,1,1:1:5"),
            "malformed light 'dir:1,2,3:1,1,1:1:5': expected dir:x,y,z[:r,g,b[:intensity]] or point:x,y,z[:r,g,b[:intensity]]");
  EXPECT_EQ(error("dir:1,2"), "light 'dir:1,2': the direction needs 3 numbers, got 2");
  EXPECT_EQ(error("point:1,2"), "light 'point:1,2': the position needs 3 numbers, got 2");
  EXPECT_EQ(error("dir:0,0,0"), "light 'dir:0,0,0': the direction must be finite and non-zero");
  EXPECT_EQ(error("point:1,2,3:1,x,1"), "the colour of light 'point:1,2,3:1,x,1': 'x' is not a number");
  EXPECT_EQ(error("dir:1,2,3:1,1,1:-1"), "light 'dir:1,2,3:1,1,1:-1': colour and intensity must be finite and ≥ 0");
  EXPECT_EQ(error("dir:1,2,3:1,1,1:1,2"), "light 'dir:1,2,3:1,1,1:1,2': the intensity needs 1 numbers, got 2");
}

TEST(ParseToneMap, ReadsNoneAndAcesOnly) {
  EXPECT_EQ(parse_tone_map("aces"), render::ToneMap::aces);
  EXPECT_EQ(parse_tone_map("none"), render::ToneMap::none);
  EXPECT_EQ(error_of([] { parse_tone_map("reinhard"); }), "unknown tone map 'reinhard': expected none or aces");
}

TEST(ParseExrPixel, ReadsHalfAndFloatOnly) {
  EXPECT_EQ(parse_exr_pixel("half"), render::ExrPixel::half);
  EXPECT_EQ(parse_exr_pixel("float"), render::ExrPixel::float32);
  EXPECT_EQ(error_of([] { parse_exr_pixel("double"); }), "unknown EXR pixel type 'double': expected half or float");
}

TEST(SettingsOf, ReadsWidthByHeightAndNamesTheOptionOtherwise) {
  const render::RenderSettings s = settings_of("640x480");
  EXPECT_EQ(s.width, 640);
  EXPECT_EQ(s.height, 480);
  for (const char* bad : {"16x", "x16", "16", "16x16x", "ax4", "16x-"})
    EXPECT_EQ(error_of([&] { settings_of(bad); }),
              fmt::format("malformed --size '{}': expected WIDTHxHEIGHT, e.g. 512x512", bad));
}

TEST(ParseColour, ReadsThreeNumbersNamingTheOption) {
  EXPECT_EQ(parse_colour("--diffuse", "0.1,0.2,0.3"), (render::Rgb{0.1, 0.2, 0.3}));
  EXPECT_EQ(error_of([] { parse_colour("--diffuse", "1,2"); }), "--diffuse '1,2': expected r,g,b");
  EXPECT_EQ(error_of([] { parse_colour("--ambient", "a,b,c"); }), "--ambient: value: 'a' is not a number");
  EXPECT_EQ(rgb_text({0.55, 0.12, 0.1}), "0.55,0.12,0.1");
}

// Parses `args` (after the command name) into SceneOptions registered on a bare command.
SceneOptions parsed(Picture picture, std::vector<std::string> args) {
  CLI::App app;
  SceneOptions o;
  o.add_to(app, picture);
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  app.parse(args);
  return o;
}

TEST(SceneOptions, BecomeATypedSceneDescription) {
  const SceneOptions none = parsed(Picture::compare, {});
  EXPECT_EQ(none.size, "384x384");
  EXPECT_EQ(parsed(Picture::render, {}).size, "512x512");
  const render::SceneDescription plain = none.description();
  EXPECT_TRUE(plain.mesh.empty());
  EXPECT_FALSE(plain.lights.has_value());
  EXPECT_FALSE(plain.diffuse || plain.specular || plain.ambient);

  const SceneOptions o = parsed(Picture::compare, {"--light", "dir:1,1,2", "--light", "point:-3,2,4:1,0.9,0.8:30",
                                                   "--diffuse", "0.1,0.2,0.3", "--ambient", "0,0,0",
                                                   "--exposure", "1.5", "--tonemap", "aces", "--size", "32x16"});
  const render::SceneDescription d = o.description();
  ASSERT_TRUE(d.lights.has_value());
  ASSERT_EQ(d.lights->size(), 2u);
  EXPECT_EQ(render::to_string((*d.lights)[1]), "point:-3,2,4:1,0.9,0.8:30");
  EXPECT_EQ(d.diffuse, (render::Rgb{0.1, 0.2, 0.3}));
  EXPECT_FALSE(d.specular.has_value());
  EXPECT_EQ(d.ambient, (render::Rgb{0, 0, 0}));
  const render::Display display = o.display();
  EXPECT_EQ(display.exposure, 1.5);
  EXPECT_EQ(display.tone_map, render::ToneMap::aces);
  EXPECT_EQ(o.settings().width, 32);
  EXPECT_EQ(o.settings().height, 16);

  const render::Scene scene = render::make_scene(make_model("phong"), d);
  const render::Metadata meta = scene_metadata(scene);
  ASSERT_EQ(meta.size(), 4u);
  EXPECT_EQ(meta[0], (std::pair<std::string, std::string>{"lights", "dir:1,1,2:1,1,1:1 point:-3,2,4:1,0.9,0.8:30"}));
  EXPECT_EQ(meta[1], (std::pair<std::string, std::string>{"diffuse", "0.1,0.2,0.3"}));
  EXPECT_EQ(meta[2], (std::pair<std::string, std::string>{"specular", "0.4,0.4,0.4"}));
}

TEST(SceneOptions, FindTheFirstErrorInTheOrderTheCommandsAlwaysHad) {
  // The mesh before the lights, the lights before the colours.
  SceneOptions o = parsed(Picture::render, {"--scene", "/nonexistent/mesh.obj", "--light", "bad", "--diffuse", "1"});
  EXPECT_THAT(error_of([&] { o.description(); }), HasSubstr("cannot read '/nonexistent/mesh.obj'"));
  o.mesh = "sphere";
  EXPECT_THAT(error_of([&] { o.description(); }), HasSubstr("malformed light 'bad'"));
  o.lights.clear();
  EXPECT_EQ(error_of([&] { o.description(); }), "--diffuse '1': expected r,g,b");
  o.exposure = INFINITY;
  EXPECT_EQ(error_of([&] { o.display(); }), "--exposure inf is not finite");
}

TEST(SceneOptions, RenderAloneHasScene) {
  CLI::App render, compare;
  SceneOptions a, b;
  a.add_to(render, Picture::render);
  b.add_to(compare, Picture::compare);
  EXPECT_NE(render.get_option_no_throw("--scene"), nullptr);
  EXPECT_EQ(compare.get_option_no_throw("--scene"), nullptr);
  for (const char* name : {"--size", "--light", "--diffuse", "--specular", "--ambient", "--exposure", "--tonemap"}) {
    EXPECT_NE(render.get_option_no_throw(name), nullptr) << name;
    EXPECT_NE(compare.get_option_no_throw(name), nullptr) << name;
  }
}

}  // namespace
}  // namespace specula::cli
