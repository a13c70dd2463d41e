#include "spirv.h"

#include <atomic>
#include <cstdint>
#include <cstring>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "process.h"
#include "specula/catalogue/catalogue.h"
#include "specula/glsl/glsl.h"
#include "specula/interrupt/interrupt.h"
#include "specula/io/files.h"

namespace specula::design {

namespace {

constexpr std::uint32_t kMagic = 0x07230203;
constexpr std::uint32_t kOpFunction = 54;
constexpr std::uint32_t kOpFunctionEnd = 56;

std::string fragment_shader(const Model& m) {
  return "#version 450\n"
         "layout(location = 0) in vec3 v_normal;\n"
         "layout(location = 1) in vec3 v_light;\n"
         "layout(location = 2) in vec3 v_view;\n"
         "layout(location = 0) out vec4 o_colour;\n"
         "layout(set = 0, binding = 0) uniform Params { vec4 params; };\n" +
         glsl::model_glsl(m) +
         "void main() {\n"
         "  o_colour = vec4(specula_brdf(normalize(v_normal), normalize(v_light), normalize(v_view), params));\n"
         "}\n";
}

// A fragment shader calling `f` (GLSL of an expression in the per-pixel variables, then the
// parameter) as specula_term, the variables from the input, the parameter a uniform.
std::string function_shader(const expr::Expression& f, std::size_t variables) {
  const std::vector<std::string>& names = f.variables();
  std::string arguments, call;
  for (std::size_t i = 0; i < names.size(); ++i) {
    arguments += fmt::format("{}float {}", i ? ", " : "", names[i]);
    call += i ? ", " : "";
    call += i < variables ? fmt::format("v_in[{}]", i) : "params.x";
  }
  return fmt::format(
      "#version 450\n"
      "layout(location = 0) in vec4 v_in;\n"
      "layout(location = 0) out vec4 o_colour;\n"
      "layout(set = 0, binding = 0) uniform Params {{ vec4 params; }};\n"
      "float specula_term({}) {{\n  return {};\n}}\n"
      "void main() {{\n  o_colour = vec4(specula_term({}));\n}}\n",
      arguments, expr::to_glsl(f), call);
}

std::optional<int> shader_instructions(const std::string& shader, const std::filesystem::path& dir, const std::string& name,
                                       const std::function<bool()>& stop, std::string& why) {
  const auto source = dir / (name + ".frag"), binary = dir / (name + ".spv"), log = dir / (name + ".log");
  std::ofstream(source) << shader;
  int status = 0;
  try {
    status = run_process({"glslangValidator", "-V", "-o", binary.string(), source.string()}, log, stop,
                         std::chrono::seconds(60));
  } catch (const Interrupted&) {
    throw;
  } catch (const std::runtime_error& e) {
    why = e.what();
    return std::nullopt;
  }
  if (status != 0) {
    why = fmt::format("glslangValidator refused the shader: {}", first_error(log));
    return std::nullopt;
  }
  const auto count = spirv_function_instructions(io::read_file(binary));
  if (!count) why = "glslangValidator's output is not SPIR-V";
  return count;
}

}  // namespace

std::optional<int> spirv_function_instructions(const std::string& binary) {
  if (binary.size() < 20 || binary.size() % 4 != 0) return std::nullopt;
  std::vector<std::uint32_t> words(binary.size() / 4);
  std::memcpy(words.data(), binary.data(), binary.size());
  if (words[0] != kMagic) return std::nullopt;
  int count = 0;
  bool inside = false;
  for (std::size_t i = 5; i < words.size();) {
    const std::uint32_t length = words[i] >> 16, opcode = words[i] & 0xffff;
    if (length == 0 || i + length > words.size()) return std::nullopt;
    if (opcode == kOpFunction) inside = true;
    if (inside) ++count;
    if (opcode == kOpFunctionEnd) inside = false;
    i += length;
  }
  return count;
}

std::optional<int> lobe_spirv_instructions(const Model& lobe_model, const std::filesystem::path& work_dir,
                                           const std::function<bool()>& stop, std::string& why) {
  static std::atomic<int> serial = 0;
  const std::string name = fmt::format("lobe{}", serial++);
  const auto lobe = shader_instructions(fragment_shader(lobe_model), work_dir, name, stop, why);
  const auto baseline =
      shader_instructions(fragment_shader(make_model("lobe: c", {}, lobe_model.form())), work_dir, name + "c", stop, why);
  if (!lobe || !baseline) return std::nullopt;
  return *lobe - *baseline;
}

std::optional<int> function_spirv_instructions(const expr::Expression& f, std::size_t variables,
                                               const std::filesystem::path& work_dir,
                                               const std::function<bool()>& stop, std::string& why) {
  static std::atomic<int> serial = 0;
  const std::string name = fmt::format("term{}", serial++);
  const expr::Expression first({{expr::Op::variable, 0, 0}}, f.variables());
  const auto term = shader_instructions(function_shader(f, variables), work_dir, name, stop, why);
  const auto baseline = shader_instructions(function_shader(first, variables), work_dir, name + "v", stop, why);
  if (!term || !baseline) return std::nullopt;
  return *term - *baseline;
}

}  // namespace specula::design
