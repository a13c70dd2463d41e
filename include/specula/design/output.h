#pragma once
// What `specula design` writes (docs/designer.md): front.csv (members and references, one row
// each), models.toml (a model file with every member bare and normalized), and the table it prints.
#include <filesystem>
#include <string>

#include "specula/design/design.h"

namespace specula::design {

/// front.csv: id, kind (member|reference), formula, max_abs_error, argmax_c, argmax_param,
/// max_rel_error, ns_per_eval, cost_vs_log, ops, spirv_instructions, model_cost, shape, timing,
/// k, check, normalization (k(p) in closed form, or quadrature).
std::string front_csv(const Result& result);

/// A member as a user model (docs/models.md): the keys of its models.toml entry, which
/// `specula serve` sends as a definition object.
struct MemberModel {
  std::string id, name, summary;
  Form form = Form::rv;
  std::string lobe;           ///< F in c and the parameter
  std::string normalization;  ///< "none" (bare), k(p) in closed form, or "quadrature"
  std::string param;          ///< the range parameter: default timing_param, min lo, max hi
  double default_value = 0, min = 0, max = 0;
};
/// Member l bare (ID) or normalized (ID-normalized).
MemberModel member_model(const Result& result, const Lobe& l, bool normalized);

/// models.toml: for every member ID (the bare lobe, normalization none) and ID-normalized
/// (k(p) in closed form where derived, else by quadrature), with the range parameter's range;
/// for an empty front, `model = []`: a model file that loads with no models.
std::string models_toml(const Result& result);

/// The front as a plain-text table, members then references.
std::string front_table(const Result& result);

/// design.json: the settings and every member (formula, shape, errors, cost), what --merge reads.
std::string design_json(const Result& result);
/// The result a design.json holds (settings and members; no references; `source` its path). Reads
/// at most Ranges::design_json_bytes and Ranges::front_members members; validates the settings as
/// the CLI does (validate(), parse_form, parse_operations) and each member's claims (a formula
/// that is a lobe in c and the parameter, errors ≥ 0, the objective's finite, argmaxes in the
/// domain, model_cost in [0, max_cost]). Throws InvalidField "merge", one line naming the file and
/// the key ("merge: D/design.json: 'members'[3].'formula' must be a string").
Result read_design(const std::filesystem::path& dir);

/// Writes front.csv, models.toml and design.json into the directory `dir` (a staged one: io::StagedDirectory).
void write_files(const Result& result, const std::filesystem::path& dir);

}  // namespace specula::design
