#pragma once
// Model text in generated source. A model's name, summary, source and origin, its formula's text
// and an inline model's id come from a model file, a --model argument or a request: anything. Every
// emitter (glsl, exports, queries, render, fit, the CLI's lut) prints such text into a comment
// through comment_text only, so that no model puts code into a shader or header (docs/exports.md).
#include <string>
#include <string_view>

namespace specula::expr {

/// `text` as the body of a one-line comment, the same in every language specula writes: GLSL,
/// HLSL, Metal (C++14, whose trigraphs turn "??/" into a backslash), C++, a .brdf file's `#`
/// lines, LaTeX's `%`. Control characters become spaces; docs/math.md's symbols are spelled in
/// ASCII (π: pi) and any other non-ASCII character is one '?'; "/*", "*/" and "??" get a space
/// between their two characters; trailing spaces go, and a backslash left last (a line splice)
/// becomes '/'.
std::string comment_text(std::string_view text);

}  // namespace specula::expr
