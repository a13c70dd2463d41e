#pragma once
// What every report section shares: the output folder, data tables written as CSV and JSON,
// figures written as SVG/PNG and inlined in the page, and the findings the claims table reads.
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "specula/report/plot.h"
#include "specula/report/report.h"

namespace specula::report {

/// A table cell: a number (written with full precision) or text.
using Cell = std::variant<double, std::string>;

struct DataTable {
  std::string name;  ///< file stem: name.csv and name.json
  std::vector<std::string> columns;
  std::vector<std::vector<Cell>> rows;
};

std::string to_csv(const DataTable& table);
std::string to_json(const DataTable& table);

/// An HTML table; `header` and every row hold ready-made cell HTML (escaped by the caller with
/// xml_escape, plot.h).
std::string html_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows,
                       const std::string& css_class = "");

/// A number the way the page shows it: `digits` significant digits, scientific when tiny or huge.
std::string show(double value, int digits = 4);

/// One value the claims table compares with the paper (filled by the sections that measure it).
struct Finding {
  double value = 0;
  std::string text;  ///< how the section phrased it, ready for the verdict column
};

class Context {
 public:
  explicit Context(const Options& options);

  bool quick() const noexcept { return options_.quick; }
  const design::GpuTimer& gpu_timer() const noexcept { return options_.gpu_timer; }
  const std::filesystem::path& dir() const noexcept { return options_.out_dir; }
  void progress(std::string_view what) const { options_.progress(what); }

  /// Writes table.csv and table.json; returns the links to both for a caption.
  std::string save(const DataTable& table);
  /// Writes name.svg and returns a <figure> with the SVG inline, the caption, the command that
  /// regenerates the data, and links to the figure's files.
  std::string svg_figure(const std::string& name, const std::string& svg, const std::string& caption,
                         const std::string& command, const std::string& data_links = "");
  /// Writes name.png (already encoded) and returns a <figure> with it inline as a data URI.
  std::string png_figure(const std::string& name, const std::string& png_bytes, const std::string& caption,
                         const std::string& command, const std::string& data_links = "");

  std::map<std::string, Finding> findings;
  /// Every file written, relative to dir(), in order.
  const std::vector<std::string>& files() const noexcept { return files_; }
  void write(const std::string& name, const std::string& bytes);

 private:
  std::string figure(const std::string& name, const std::string& body, const std::string& caption,
                     const std::string& command, const std::string& links);

  Options options_;
  std::vector<std::string> files_;
};

/// A section of the page: its anchor, its heading and its HTML body.
struct Section {
  std::string id;
  std::string title;
  std::string html;
};

}  // namespace specula::report
