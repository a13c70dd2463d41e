// specula export: a model as HLSL, Metal, a BRDF Explorer file or a C++ header (docs/exports.md).
#include "cli.h"
#include "specula/exports/exports.h"

namespace specula::cli {
namespace {

struct ExportOptions {
  ModelOptions model;
  std::string format;
  std::string out;
};

}  // namespace

void add_export_command(CLI::App& app) {
  auto o = std::make_shared<ExportOptions>();
  auto* cmd = app.add_subcommand("export", "A model as HLSL, Metal, a BRDF Explorer .brdf file or a C++ header");
  o->model.add_to(*cmd);
  o->model.add_coef_to(*cmd);
  cmd->add_option("--format", o->format,
                  "hlsl (HLSL functions), msl (Metal Shading Language functions), brdf (a Disney BRDF Explorer "
                  "file), cpp (a C++ header in double that needs only <cmath>)")
      ->required();
  cmd->add_option("--out,-o", o->out, "Write to FILE (atomically) instead of stdout");
  cmd->footer(
      "Every format is written from the definitions `specula glsl` uses: the same functions and the same\n"
      "normalization, computed from the parameters (the log lobe's coef(n) by its Chebyshev series).\n"
      "  hlsl, msl  float specula_brdf(float3 N, float3 L, float3 V, float4 params), as in `specula glsl`\n"
      "  brdf       analytic; one slider per parameter; vec3 BRDF(vec3 L, vec3 V, vec3 N, vec3 X, vec3 Y)\n"
      "  cpp        namespace specula_export_<id>: double f(N, L, V); Sample sample(wi, u1, u2); double pdf(wi, wo)\n"
      "Examples:\n"
      "  specula export --model ggx -p alpha=0.2 --format hlsl -o ggx.hlsl\n"
      "  specula export --model log-normalized -p n=50 --format brdf -o log.brdf\n"
      "  specula export --model 'lobe: c^n' --coef 3.5 --format cpp -o lobe.h\n"
      "  specula export --model ggx+ms -p alpha=0.5 --format cpp -o ggx_ms.h   (compensated: its table baked in)");
  cmd->callback([o] { write_output(o->out, exports::export_model(o->model.make(), exports::parse_format(o->format))); });
}

}  // namespace specula::cli
