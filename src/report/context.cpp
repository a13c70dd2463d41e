#include "context.h"

#include "specula/io/base64.h"

#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "specula/exceptions.h"
#include "specula/io/files.h"
#include "specula/io/table.h"

namespace specula::report {
namespace {

std::string csv_cell(const Cell& cell) {
  if (const double* v = std::get_if<double>(&cell)) return io::format_number(*v);
  const std::string& text = std::get<std::string>(cell);
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char ch : text) quoted += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return quoted + "\"";
}

}  // namespace

std::string to_csv(const DataTable& table) {
  std::string out;
  auto line = [&out](const auto& cells, auto text_of) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (i) out += ',';
      out += text_of(cells[i]);
    }
    out += '\n';
  };
  line(table.columns, [](const std::string& name) { return name; });
  for (const auto& row : table.rows) line(row, csv_cell);
  return out;
}

std::string to_json(const DataTable& table) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const auto& row : table.rows) {
    nlohmann::ordered_json object;
    for (std::size_t i = 0; i < row.size() && i < table.columns.size(); ++i) {
      if (const double* v = std::get_if<double>(&row[i]))
        object[table.columns[i]] = std::isfinite(*v) ? nlohmann::ordered_json(*v) : nlohmann::ordered_json();
      else
        object[table.columns[i]] = std::get<std::string>(row[i]);
    }
    rows.push_back(std::move(object));
  }
  return nlohmann::ordered_json{{"table", table.name}, {"columns", table.columns}, {"rows", rows}}.dump(1) + "\n";
}

std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                       const std::string& css_class) {
  std::string out = css_class.empty() ? "<table><thead><tr>" : fmt::format("<table class=\"{}\"><thead><tr>", css_class);
  for (const auto& h : header) out += "<th>" + h + "</th>";
  out += "</tr></thead>\n<tbody>\n";
  for (const auto& row : rows) {
    out += "<tr>";
    for (const auto& cell : row) out += cell.rfind("<td", 0) == 0 ? cell : "<td>" + cell + "</td>";
    out += "</tr>\n";
  }
  return out + "</tbody></table>\n";
}

std::string show(double value, int digits) {
  if (!std::isfinite(value)) return std::isnan(value) ? "—" : (value > 0 ? "∞" : "−∞");
  std::string text = fmt::format("{:.{}g}", value, digits);
  if (const auto e = text.find('e'); e != std::string::npos) {
    const int exponent = std::stoi(text.substr(e + 1));
    text = fmt::format("{}·10<sup>{}</sup>", text.substr(0, e), exponent < 0 ? fmt::format("−{}", -exponent)
                                                                              : std::to_string(exponent));
  }
  return text[0] == '-' ? fmt::format("−{}", text.substr(1)) : text;
}

Context::Context(const Options& options) : options_(options) {}

void Context::write(const std::string& name, const std::string& bytes) {
  io::write_file_atomically(options_.out_dir / name, bytes);
  files_.push_back(name);
}

std::string Context::save(const DataTable& table) {
  write(table.name + ".csv", to_csv(table));
  write(table.name + ".json", to_json(table));
  return fmt::format("<a href=\"{0}.csv\">{0}.csv</a>, <a href=\"{0}.json\">{0}.json</a>", table.name);
}

std::string Context::figure(const std::string& name, const std::string& body, const std::string& caption,
                            const std::string& command, const std::string& links) {
  std::string out = fmt::format("<figure id=\"{}\">\n{}<figcaption>{}", name, body, caption);
  if (!command.empty()) out += fmt::format("<br><span class=\"cmd\">Regenerate: <code>{}</code></span>", xml_escape(command));
  out += fmt::format("<br><span class=\"files\">Files: {}</span>", links);
  return out + "</figcaption></figure>\n";
}

std::string Context::svg_figure(const std::string& name, const std::string& svg, const std::string& caption,
                                const std::string& command, const std::string& data_links) {
  write(name + ".svg", svg);
  // Inline SVG in HTML needs no namespace declaration: the page holds no URL at all.
  std::string inline_svg = svg;
  const std::string xmlns = " xmlns=\"http://www.w3.org/2000/svg\"";
  if (const auto at = inline_svg.find(xmlns); at != std::string::npos) inline_svg.erase(at, xmlns.size());
  return figure(name, inline_svg, caption, command,
                data_links + (data_links.empty() ? "" : ", ") + fmt::format("<a href=\"{0}.svg\">{0}.svg</a>", name));
}

std::string Context::png_figure(const std::string& name, const std::string& png_bytes, const std::string& caption,
                                const std::string& command, const std::string& data_links) {
  write(name + ".png", png_bytes);
  const std::string img = fmt::format("<img src=\"data:image/png;base64,{}\" alt=\"{}\">\n", io::base64(png_bytes),
                                      xml_escape(name));
  return figure(name, img, caption, command,
                data_links + (data_links.empty() ? "" : ", ") + fmt::format("<a href=\"{0}.png\">{0}.png</a>", name));
}

}  // namespace specula::report
