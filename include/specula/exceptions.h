#pragma once
// The one exception type specula throws for bad input (unknown model, parameter out of range,
// malformed range or expression), and InvalidField, which names the field at fault by its key and
// spells it in the message as the interface that asked does (Spelling). The CLI turns either into
// one line on stderr and exit code 2. Below it, the floor every module stands on for its enums:
// unreachable() after a switch that lists every enumerator, and the names of an enum from one
// list, which parsing, messages and the interfaces' checks all read (the end of this file).
#include <array>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace specula {

class InvalidArgument : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

/// Bad input in one named field of a request: `field` is its key ("theta_i", "params", "n"),
/// whatever the interface that spelled it in the message (the CLI's --theta-i, the server's
/// JSON key). The server answers it with {"error": message, "field": field}.
class InvalidField : public InvalidArgument {
 public:
  InvalidField(std::string field, const std::string& message)
      : InvalidArgument(message), field_(std::move(field)) {}
  const std::string& field() const noexcept { return field_; }

 private:
  std::string field_;
};

/// How an interface names a field in its messages: a library that checks a value a user chose
/// takes the Spelling of the interface that asks, so that its message names the field as the
/// user wrote it.
enum class Spelling {
  option,  ///< the CLI: "theta_i" → "--theta-i", "params" → "--param"
  key      ///< the server: the JSON key itself
};

/// `key` as `spelling` spells it.
inline std::string spelled(std::string_view key, Spelling spelling) {
  if (spelling == Spelling::key) return std::string(key);
  if (key == "params") return "--param";
  std::string option = "--";
  for (const char ch : key) option += ch == '_' ? '-' : ch;
  return option;
}

/// `message` as exactly one line of text: control characters (a newline or tab inside a user's
/// argument echoed back, an escape sequence) are written as C escapes (\n, \t, \x1b), so that
/// an error printed by the CLI is always one line, whatever the input it quotes.
inline std::string one_line(std::string_view message) {
  std::string out;
  out.reserve(message.size());
  for (const char c : message) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else if (c == '\t') out += "\\t";
    else if (byte < 0x20 || byte == 0x7f) {
      char escaped[5];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", byte);
      out += escaped;
    } else out += c;
  }
  return out;
}

// ---- Enums: their switches and their tables --------------------------------------------------
//
// A switch over an enum lists every enumerator and has no default: -Werror=switch (CMakeLists.txt)
// then fails the build on an enumerator that a switch forgot. Where the function must still end
// after the switch, it calls unreachable(): only a value outside the enum (a bad cast) gets there.
//
// An enum's enumerators are 0, 1, …, count − 1, and the count sits beside the enum:
//     inline constexpr std::size_t kFormCount = static_cast<std::size_t>(Form::nh) + 1;
// A table indexed by the enum is a std::array<T, kFormCount>, or is checked against the count by a
// static_assert. The enum's names are one constexpr switch over every enumerator, returning "" for
// a value outside the enum; parsing (enum_named), listing (names_listed) and printing all read that
// switch, and
//     static_assert(names_complete<Form, kFormCount>([](Form f) { return to_string(f); }));
// fails the build on a name that is empty or repeated, and on a count that a new enumerator (named
// in the switch, as -Werror=switch insists) has outgrown.

/// C++23's std::unreachable(), but defined: a value outside its enum reached the end of a switch
/// that returns for every enumerator. Aborts.
[[noreturn]] inline void unreachable() noexcept { std::abort(); }

/// Every enumerator of E, in order: E(0), …, E(count − 1).
template <class E, std::size_t count>
constexpr std::array<E, count> enumerators() noexcept {
  std::array<E, count> all{};
  for (std::size_t i = 0; i < count; ++i) all[i] = static_cast<E>(i);
  return all;
}

/// Whether name(E(i)) for i < count are non-empty and distinct and name(E(count)) is "": the names
/// cover exactly the enumerators 0 … count − 1.
template <class E, std::size_t count, class Name>
constexpr bool names_complete(Name name) {
  for (std::size_t i = 0; i < count; ++i) {
    const std::string_view text = name(static_cast<E>(i));
    if (text.empty()) return false;
    for (std::size_t j = 0; j < i; ++j)
      if (std::string_view(name(static_cast<E>(j))) == text) return false;
  }
  return std::string_view(name(static_cast<E>(count))).empty();
}

/// The enumerator whose name(e) is `text`, if any.
template <class E, std::size_t count, class Name>
constexpr std::optional<E> enum_named(std::string_view text, Name name) {
  for (std::size_t i = 0; i < count; ++i)
    if (std::string_view(name(static_cast<E>(i))) == text) return static_cast<E>(i);
  return std::nullopt;
}

/// The names in order, for messages and help: "a, b or c" (`last` before the last name, ", "
/// before the others), or with `between` and `last` both " | ": "a | b | c".
template <class E, std::size_t count, class Name>
std::string names_listed(Name name, std::string_view last = " or ", std::string_view between = ", ") {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) {
    if (i > 0) text += i + 1 == count ? last : between;
    text += std::string_view(name(static_cast<E>(i)));
  }
  return text;
}

/// An enum's to_string (found in the enum's namespace) as the `name` of the helpers below: the
/// default where an enum's to_string is its one list of names.
struct ToString {
  template <class E>
  constexpr auto operator()(E e) const {
    return to_string(e);
  }
};

/// The names in order, as a list of strings: what a CLI option's CLI::IsMember check reads.
template <class E, std::size_t count, class Name = ToString>
std::vector<std::string> names_of(Name name = {}) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < count; ++i) names.emplace_back(name(static_cast<E>(i)));
  return names;
}

/// The enumerator of E named `text`; else InvalidField `key`, "KEY must be one of a, b, c, got
/// 'text'" with KEY as `spelling` spells it. Where an interface reads a choice (an option, a
/// request's field) into its enum, from the same names as names_of.
template <class E, std::size_t count, class Name = ToString>
E choice_named(std::string_view key, std::string_view text, Spelling spelling, Name name = {}) {
  if (const auto value = enum_named<E, count>(text, name)) return *value;
  throw InvalidField(std::string(key), spelled(key, spelling) + " must be one of " +
                                           names_listed<E, count>(name, ", ") + ", got '" + std::string(text) + "'");
}

}  // namespace specula
