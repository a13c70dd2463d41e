// GLSL for formula models (src/glsl/formula_glsl.h): each step printed by expr::to_glsl with the
// slots renamed.
#include "formula_glsl.h"

#include <fmt/format.h>

namespace specula::glsl {
namespace {

/// `e` over GLSL names: inputs kept, parameters p_NAME, lets l_NAME.
expr::Expression renamed(const expr::Expression& e, const expr::Program& program) {
  std::vector<std::string> names;
  const auto slots = program.slot_names();
  const std::size_t params_end = program.input_count() + program.param_count();
  for (std::size_t i = 0; i < e.variables().size(); ++i) {
    if (i < program.input_count()) names.push_back(slots[i]);
    else if (i < params_end) names.push_back(glsl_param_name(slots[i]));
    else names.push_back("l_" + slots[i]);
  }
  return expr::Expression({e.nodes().begin(), e.nodes().end()}, std::move(names));
}

}  // namespace

std::string glsl_param_name(std::string_view name) { return "p_" + std::string(name); }

std::string program_lines(const expr::Program& program, FormulaPrinter print) {
  std::string lines;
  const std::size_t first_let = program.input_count() + program.param_count();
  for (std::size_t i = 0; i < program.lets().size(); ++i)
    lines += fmt::format("  float l_{} = {};\n", program.slot_names()[first_let + i],
                         print(renamed(program.lets()[i], program)));
  return lines + fmt::format("  return {};\n", print(renamed(program.result(), program)));
}

std::string coefficient_formula(const expr::Program& coefficient, FormulaPrinter print) {
  return fmt::format("({})", print(renamed(coefficient.result(), coefficient)));
}

}  // namespace specula::glsl
