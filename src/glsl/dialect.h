#pragma once
// Private to src/glsl: the model's GLSL rewritten in another language (glsl.h's Language). The
// GLSL of src/glsl/shaders/ and of the emitter uses a small subset — float, vec2..vec4, global
// `const float`, and the built-in functions of kBuiltins — which maps word for word onto HLSL,
// the Metal Shading Language and C++ (double, over the vector type of cpp_support()).
#include <string>
#include <string_view>

#include "specula/glsl/glsl.h"

namespace specula::glsl {

/// `glsl` (functions and global constants, `//` comments) in `language`: types, built-in function
/// names and global constants respelled, comments kept as they are. Throws std::logic_error for a
/// GLSL built-in function the rewrite does not know (a shader file that uses more of GLSL).
std::string translate(std::string_view glsl, Language language);

/// C++ that translate(…, Language::cpp) compiles against: Vec2 and Vec3 (double) with GLSL's
/// operators, and GLSL's built-in functions over double; needs <cmath>.
std::string_view cpp_support();

}  // namespace specula::glsl
