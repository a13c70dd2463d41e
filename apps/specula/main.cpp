// specula: design, check and ship energy-conserving specular lobes. One command per file.
#include <fmt/format.h>
#include <iostream>

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
#endif

#include "build_info.h"
#include "cli.h"
#include "specula/exceptions.h"
#include "specula/interrupt/interrupt.h"
#include "specula/catalogue/model_file.h"
#include "stop_signals.h"

namespace {

int run(int argc, char** argv) {
  const specula::cli::StopSignals stop_signals;  // first: before any thread starts
  CLI::App app{"specula: design, check and ship fast, energy-conserving specular lobes.\n"
               "Run `specula COMMAND --help` for a command's options and an example.",
               "specula"};
  app.require_subcommand(1);
  // --version: version, commit and SIMD target on one line (exit 0), before any subcommand is due.
  app.set_version_flag("--version,-V", [] { return specula::cli::version_line(); },
                       "Print the version, the git commit and the SIMD target, and exit");
  // --models FILE before or after the command: every command sees the file's models as its own.
  app.fallthrough();
  std::vector<std::string> model_files;
  app.add_option("--models", model_files, "A model file (TOML, docs/models.md) whose models every command can use "
                             "by id; repeatable")
      ->each([](const std::string& file) { specula::register_model_file(file); })
      ->type_name("FILE");
  app.footer("Every command takes --models FILE (your own models, docs/models.md) and, wherever it takes a\n"
             "model id, an inline model: --model 'lobe: FORMULA in c' or --model 'brdf: FORMULA in nl nv nh vh lv'.\n"
             "Example:\n  specula normalize --model log --n 1:7 --round 3   # the paper's Fig. 5 table");
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "specula: error: " + specula::one_line(e.what()) + " (see --help)\n";
  });
  specula::cli::add_models_command(app);
  specula::cli::add_eval_command(app);
  specula::cli::add_normalize_command(app);
  specula::cli::add_albedo_command(app);
  specula::cli::add_check_command(app);
  specula::cli::add_error_command(app);
  specula::cli::add_fit_command(app);
  specula::cli::add_design_command(app);
  specula::cli::add_sample_command(app);
  specula::cli::add_render_command(app);
  specula::cli::add_compare_command(app);
  specula::cli::add_glsl_command(app);
  specula::cli::add_export_command(app);
  specula::cli::add_lut_command(app);
  specula::cli::add_walk_command(app);
  specula::cli::add_verdict_command(app);
  specula::cli::add_report_command(app);
  specula::cli::add_bench_command(app);
  specula::cli::add_serve_command(app);
  specula::cli::make_integer_options_strict(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const specula::cli::CheckFailed&) {
    return 1;
  } catch (const CLI::ParseError& e) {
    app.exit(e);
    return 2;
  } catch (const specula::Interrupted& e) {
    std::cerr << "specula: stopped: " << e.what() << '\n';
    return e.signal() ? specula::cli::exit_code_for_signal(e.signal()) : 1;
  } catch (const specula::InvalidArgument& e) {
    std::cerr << "specula: error: " << specula::one_line(e.what()) << '\n';
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "specula: internal error: " << specula::one_line(e.what()) << '\n';
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const int code = run(argc, argv);
#if defined(__SANITIZE_ADDRESS__)
  // LeakSanitizer's check now, while the worker threads (oneTBB's, Mesa's llvmpipe after a GL
  // render) are idle, instead of at exit, where its tracer can crash on a thread being torn down.
  __lsan_do_leak_check();
#endif
  return code;
}
