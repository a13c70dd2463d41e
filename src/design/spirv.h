#pragma once
// A GPU proxy for a lobe's cost: the SPIR-V instructions glslang makes of its GLSL export
// (glsl::model_glsl, `glslangValidator -V`, no optimizer), beyond those of the lobe F = c in the
// same form — the lobe's own instructions, the shader around it subtracted.
#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "specula/expr/expr.h"
#include "specula/models/model.h"

namespace specula::design {

/// Instructions in the function bodies of a SPIR-V binary (words: the 5-word header, then each
/// instruction's word count in its first word's high half); nullopt if it is not SPIR-V.
std::optional<int> spirv_function_instructions(const std::string& binary);

/// The SPIR-V instructions of `lobe_model`'s GLSL beyond those of F = c in its form; nullopt
/// (and `why` says why) if glslangValidator is missing or refuses the shader.
std::optional<int> lobe_spirv_instructions(const Model& lobe_model, const std::filesystem::path& work_dir,
                                           const std::function<bool()>& stop, std::string& why);

/// The SPIR-V instructions of a function target's member (or reference) `f`, an expression in the
/// per-pixel variables and then the range parameter (if any), written as a GLSL function that a
/// fragment shader calls with the variables from its input and the parameter from a uniform,
/// beyond those of the function that returns its first variable; nullopt (and `why`) as above.
std::optional<int> function_spirv_instructions(const expr::Expression& f, std::size_t variables,
                                               const std::filesystem::path& work_dir,
                                               const std::function<bool()>& stop, std::string& why);

}  // namespace specula::design
