#include "specula/catalogue/model_meta.h"

#include "specula/io/table.h"

namespace specula {

std::vector<std::pair<std::string, std::string>> model_meta(const Model& m) {
  std::vector<std::pair<std::string, std::string>> meta{{"model", std::string(m.id())}};
  for (std::size_t i = 0; i < m.params().size(); ++i)
    meta.emplace_back(std::string(m.info().params[i].name), io::format_number(m.params()[i]));
  if (m.is_lobe()) {
    meta.emplace_back("form", to_string(m.form()));
    meta.emplace_back("coef", io::format_number(m.coef()));
  }
  return meta;
}

}  // namespace specula
