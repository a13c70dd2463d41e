// Fuzzes model files (models/model_file.h; `--models FILE`). Input: the file's bytes.
// Properties, each a finding when broken:
//   - parse_model_file() returns or throws InvalidArgument, nothing else; an error is one line
//     that starts with the file's name;
//   - every model it returns has a non-empty id, a default inside each parameter's range, and
//     can be made at its defaults (or is refused with InvalidArgument: a k that is not finite
//     and > 0); a made lobe evaluates at c = 0, ½, 1 and u = 0, 1 without throwing, and its
//     support end, half-maximum and kinks are ordered (0 ≤ kink < support, half-maximum > 0);
//   - a made model's GLSL-free properties hold whatever the formula: nothing throws when it is
//     evaluated at a few directions.
#include <cmath>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "specula/catalogue/model_file.h"

namespace {

using namespace specula;

constexpr std::string_view kSource = "fuzz.toml";

void check_lobe(const Model& m) {
  const auto& lobe = std::get<lobes::Formula>(m.lobe());
  for (const double c : {0.0, 0.5, 1.0}) (void)m.at_cos(c);
  for (const double u : {0.0, 1.0}) (void)lobe.at_log_cos(u);
  fuzz::require(!(lobe.half_max_log_cos() <= 0), "a formula lobe's half-maximum is not > 0");
  for (const double kink : lobe.kinks_log_cos())
    fuzz::require(kink >= 0 && kink < lobe.support_log_cos(), "a kink outside [0, support)");
}

void check(const ModelInfo& info) {
  fuzz::require(!info.id.empty(), "a model without an id");
  for (const auto& p : info.params) fuzz::require(p.accepts(p.default_value), "a default outside its range");
  Model model;
  if (!fuzz::accepted("make_model", [&] { model = make_model(std::make_shared<const ModelInfo>(info)); })) return;
  const Vec3 n{0, 0, 1}, l{0.6, 0, 0.8}, v{-0.6, 0, 0.8};
  (void)model(n, l, v);
  if (model.is_lobe()) check_lobe(model);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = fuzz::text_of(data, size);
  try {
    for (const auto& info : parse_model_file(text, kSource)) check(info);
  } catch (const InvalidArgument& e) {
    const std::string_view message = e.what();
    fuzz::require(message.starts_with(kSource), "a model file error does not name the file: " + std::string(message));
    fuzz::require(message.find('\n') == std::string_view::npos, "a model file error spans lines: " + std::string(message));
  } catch (const std::exception& e) {
    fuzz::finding("parse_model_file: unexpected exception " + fuzz::type_name(typeid(e)) + ": " + e.what());
  }
  return 0;
}
