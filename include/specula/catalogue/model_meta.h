#pragma once
// A model described as name = value text: what the CLI's tables and the server's JSON put beside
// their data, and the comment at the top of an export.
#include <string>
#include <utility>
#include <vector>

#include "specula/models/model.h"

namespace specula {

/// A model's metadata: its id ("model"), its parameter values by name, and form and coef for lobe
/// models, each value as io::format_number (io/table.h) writes it.
std::vector<std::pair<std::string, std::string>> model_meta(const Model& m);

}  // namespace specula
