// specula glsl: a model as a self-contained GLSL function (the paper's Fig. 10, for every model).
#include "cli.h"
#include "specula/glsl/glsl.h"
#include "specula/render/scene_shader.h"

namespace specula::cli {
namespace {

struct GlslOptions {
  ModelOptions model;
  std::string dialect = "glsl330";
  bool shader = false;
  bool vertex = false;
  std::string out;
};

std::string function_text(const GlslOptions& o) {
  const Model model = o.model.make();
  const glsl::Dialect dialect = queries::dialect_named(o.dialect);
  if (o.vertex) return render::scene_vertex_shader(dialect);
  if (o.shader) return render::scene_fragment_shader(model, dialect, render::SceneGeometry::spheres);
  return queries::glsl_function(model, dialect);
}

}  // namespace

void add_glsl_command(CLI::App& app) {
  auto o = std::make_shared<GlslOptions>();
  auto* cmd = app.add_subcommand("glsl", "A model as a self-contained GLSL function with its exact normalization");
  o->model.add_to(*cmd);
  o->model.add_coef_to(*cmd);
  cmd->add_option("--dialect", o->dialect, "glsl330 (desktop GLSL 3.30 core), gles300 (GLSL ES 3.00) or webgl2")
      ->capture_default_str()
      ->check(one_of<glsl::Dialect, glsl::kDialectCount>());
  cmd->add_flag("--shader", o->shader,
                "Print the complete fragment shader of the comparison sphere instead (the one `render --backend gl` "
                "runs; its uniforms are documented at its top)");
  cmd->add_flag("--vertex", o->vertex, "Print the matching vertex shader (a full-screen triangle from gl_VertexID)");
  cmd->add_option("--out,-o", o->out, "Write to FILE (atomically) instead of stdout");
  cmd->footer(
      "Prints the model's functions and the entry point\n"
      "  float specula_brdf(vec3 N, vec3 L, vec3 V, vec4 params)   // params = the model's parameters in order\n"
      "Normalizations are computed in the shader from the parameters: closed forms where they exist;\n"
      "the log lobe's exact coef(n) from two Chebyshev series (4e-7 relative in float, n in (0, 1e30]).\n"
      "Examples:\n"
      "  specula glsl --model log-normalized                 # the paper's Fig. 10, exactly normalized\n"
      "  specula glsl --model ggx --dialect webgl2 -o ggx.glsl\n"
      "  specula glsl --model log-normalized --shader --dialect webgl2 -o sphere.frag   # the whole sphere\n"
      "  specula glsl --model log-normalized --vertex --dialect webgl2 -o sphere.vert");
  cmd->callback([o] { write_output(o->out, function_text(*o)); });
}

}  // namespace specula::cli
