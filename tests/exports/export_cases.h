#pragma once
// The models every export test walks: each registered model (built-in, and the user-written ones of
// tests/user_models_environment.cpp) at its defaults, lobes in both forms, an inline lobe and BRDF,
// and compensated models (M+ms, and each other compensation suffix) of a BRDF and a lobe; with a C++ name for each and files in a fresh
// temporary directory.
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

#include "specula/catalogue/catalogue.h"

namespace specula::testing {

inline std::vector<Model> export_cases() {
  std::vector<Model> cases;
  for (const auto& info : models()) {
    if (info.kind == ModelKind::brdf) {
      cases.push_back(make_model(info.id));
      continue;
    }
    for (const Form form : {Form::rv, Form::nh}) cases.push_back(make_model(info.id, {}, form));
  }
  cases.push_back(make_model("lobe: max(0, 1 - n*(1-c)/4)^4", {{"n", 30}}));
  cases.push_back(make_model("brdf: rho/pi * (1 + a*nh^4)", {{"rho", 0.5}, {"a", 0.25}}));
  cases.push_back(make_model("ggx+ms", {{"alpha", 0.4}}));
  cases.push_back(make_model("log-normalized+ms", {{"n", 5}}));
  // The other compensations (models/compensated.h): the added one with its F_ms, the scaled ones
  // with a constant F_s, with Schlick's F(N·V) and with the exact dielectric's.
  cases.push_back(make_model("ggx+kulla-conty", {{"alpha", 0.4}, {"f0", 0.5}}));
  cases.push_back(make_model("ggx+cycles", {{"alpha", 0.7}, {"f0", 0.2}}));
  cases.push_back(make_model("ggx+turquin-f", {{"alpha", 0.4}, {"f0", 0.5}}));
  cases.push_back(make_model("cook-torrance-1982+turquin-f", {{"m", 0.4}}));
  return cases;
}

inline std::string case_name(const Model& model) {
  return fmt::format("{} ({})", model.id(), model.is_lobe() ? to_string(model.form()) : "brdf");
}

/// A directory of its own below the temporary one, removed with the object.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name) {
    static int counter = 0;
    path_ = std::filesystem::temp_directory_path() / fmt::format("specula-{}-{}-{}", name, ::getpid(), counter++);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  /// Writes `text` to the file `name` in the directory and returns its path.
  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto file = path_ / name;
    std::ofstream(file) << text;
    return file;
  }
  const std::filesystem::path& path() const noexcept { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace specula::testing
