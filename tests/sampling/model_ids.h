#pragma once
// The ids the sampling tests run over: every built-in model and every user-written copy of
// examples/models/builtin-copies.toml (registered for the binary by tests/user_models_environment.cpp;
// read here at start-up, before that registration, to name the tests).
#include <algorithm>
#include <string>
#include <vector>

#include "specula/models/model.h"
#include "specula/catalogue/model_file.h"

namespace specula::sampling {

inline std::vector<std::string> every_model_id() {
  std::vector<std::string> ids;
  for (const ModelInfo& info : models())
    if (info.is_builtin()) ids.push_back(info.id);
  for (const ModelInfo& info : load_model_file(SPECULA_SOURCE_DIR "/examples/models/builtin-copies.toml"))
    ids.push_back(info.id);
  return ids;
}

inline std::string test_name(const std::string& id) {
  std::string name;
  for (char ch : id) name += std::isalnum(static_cast<unsigned char>(ch)) ? ch : '_';
  return name;
}

}  // namespace specula::sampling
