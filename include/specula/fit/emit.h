#pragma once
// A fitted formula as a function in another language (C++, GLSL, LaTeX, Python), constants at
// full precision: what `specula fit --emit` prints and the server's fit jobs return.
#include <string>
#include <string_view>
#include <vector>

#include "specula/expr/expr.h"

namespace specula::fit {

/// Throws InvalidArgument unless `language` is "cpp", "glsl", "latex" or "python".
void check_language(std::string_view language);

/// "fitted_" and the target with every character an identifier cannot hold replaced by '_'.
std::string function_name(std::string_view target);

/// Throws InvalidArgument when a variable is a reserved word in `language` (it could not be a
/// parameter name there).
void check_emittable(const std::vector<std::string>& variables, std::string_view language);

/// The formula as a function named function_name(target) taking its variables, after a comment
/// line holding `origin` as expr::comment_text writes it (Python: a docstring, escaped; LaTeX: an
/// equation `target = …`).
std::string emit_function(const expr::Expression& formula, std::string_view language,
                          std::string_view target, std::string_view origin);

}  // namespace specula::fit
