// The user-written copies of every built-in family and of GGX, Cook-Torrance, Ward and Lambert
// (examples/models/builtin-copies.toml), and a lobe with six parameters (more than specula_brdf's
// vec4 holds), registered for the whole binary: every test that walks models() — GLSL in every
// dialect, GL against CPU renders — covers user-defined models as it covers the built-in ones.
#include <gtest/gtest.h>

#include "specula/catalogue/model_file.h"

namespace {

constexpr const char* kSixParameters = R"toml([[model]]
id = "six-parameters"
name = "a lobe of six parameters"
kind = "lobe"
form = "rv"
lobe = "a*c^n + b*c^(2*n) + (1 - a - b)*c^(d*n) + 0*e1*e2"
normalization = "quadrature"
[model.params.n]
default = 20
min = 1
max = 1e4
[model.params.a]
default = 0.5
min = 0
max = 1
[model.params.b]
default = 0.25
min = 0
max = 0.5
[model.params.d]
default = 3
min = 1
max = 10
[model.params.e1]
default = 1
min = 0
max = 1
[model.params.e2]
default = 1
min = 0
max = 1
)toml";

class UserModels : public ::testing::Environment {
 public:
  void SetUp() override {
    specula::register_model_file(SPECULA_SOURCE_DIR "/examples/models/builtin-copies.toml");
    specula::register_models(specula::parse_model_file(kSixParameters, "six.toml"));
  }
};

const auto* const kUserModels = ::testing::AddGlobalTestEnvironment(new UserModels);

}  // namespace
