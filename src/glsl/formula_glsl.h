#pragma once
// Private to src/gl: GLSL for user-defined (formula) models. Names in the emitted code: the inputs
// as they are (c, u; nl, nv, nh, vh, lv), parameters as p_NAME and lets as l_NAME, so that no user
// name can clash with a GLSL keyword or built-in function.
#include <string>

#include "specula/expr/program.h"
#include "specula/models/model.h"

namespace specula::glsl {

/// How a formula's expressions are printed: expr::to_glsl (float literals, GLSL's functions), or
/// expr::to_cpp (double literals, std:: functions) for C++ (Language::cpp).
using FormulaPrinter = std::string (*)(const expr::Expression&);

/// "p_NAME": a parameter's name in GLSL.
std::string glsl_param_name(std::string_view name);

/// The lines of a program's body: one `float l_NAME = …;` per let, then `return …;`.
std::string program_lines(const expr::Program& program, FormulaPrinter print);

/// The GLSL expression for k of a formula-normalized lobe, in the p_ parameters.
std::string coefficient_formula(const expr::Program& coefficient, FormulaPrinter print);

}  // namespace specula::glsl
