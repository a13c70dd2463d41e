// Fresnel channels written as text (catalogue/fresnel_spec.h): every kind read and written back,
// and what is not a channel refused with the reason.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "specula/catalogue/fresnel_spec.h"
#include "specula/exceptions.h"

namespace specula {
namespace {

using ::testing::HasSubstr;

TEST(FresnelSpec, ReadsEveryKindAndWritesItBack) {
  const fresnel::Channel s = parse_fresnel("schlick:f0=0.5,p=4");
  EXPECT_EQ(s.kind, fresnel::Kind::schlick);
  EXPECT_EQ(s.f0, 0.5);
  EXPECT_EQ(s.f90, 1);
  EXPECT_EQ(s.exponent, 4);
  EXPECT_EQ(parse_fresnel("schlick").f0, 0.04);
  for (const char* spec : {"one", "schlick:f0=0.04,f90=0.9,p=5.5", "f82:f0=0.9,tint=0.7", "dielectric:eta=0.6666666666666666",
                           "conductor:eta=0.2,kappa=3.1"}) {
    const fresnel::Channel f = parse_fresnel(spec);
    EXPECT_EQ(to_spec(f), spec);
    const fresnel::Channel back = parse_fresnel(to_spec(f));
    EXPECT_EQ(back(0.3), f(0.3)) << spec;
  }
}

TEST(FresnelSpec, RefusesWhatIsNotAChannelNamingTheProblem) {
  const auto error = [](const char* spec) {
    try {
      parse_fresnel(spec);
    } catch (const InvalidArgument& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_THAT(error("glass"), HasSubstr("unknown kind"));
  EXPECT_THAT(error("schlick:eta=1.5"), HasSubstr("not a parameter of schlick"));
  EXPECT_THAT(error("schlick:f0"), HasSubstr("not a parameter"));
  EXPECT_THAT(error("schlick:f0=0.1,f0=0.2"), HasSubstr("twice"));
  EXPECT_THAT(error("schlick:f0=abc"), HasSubstr("f0"));
  EXPECT_THAT(error("schlick:f0=1.5"), HasSubstr("outside"));
  EXPECT_THAT(error("dielectric:eta=0"), HasSubstr("eta"));
  EXPECT_THAT(error("dielectric:eta=nan"), HasSubstr("eta"));
  EXPECT_THAT(error("conductor:eta=0.2,kappa=-1"), HasSubstr("kappa"));
  EXPECT_THAT(error("one:f0=1"), HasSubstr("none"));
}

}  // namespace
}  // namespace specula
