#pragma once
/// @file params.hpp
/// Case-file parameters: a JSON value that knows which file and which JSON path it came from, so that
/// every error is one line "FILE: /json/path: reason" (lagfsi::InputError).
///
/// In the spirit of Kratos' Parameters::ValidateAndAssignDefaults: each object is checked against a
/// defaults object; keys not in the defaults are errors that list the valid keys; a value whose JSON type
/// differs from the default's is an error; missing keys take the default. A default of `null` marks a
/// required key (no default), so the defaults object documents every key in one place.
///
/// Each kind of object is declared once, as a KeyTable (its keys, defaults and one-line descriptions) next to
/// the code that reads it: the same declaration validates the object, fills the defaults that `lagfsi check`
/// prints, and generates the case-file reference (`lagfsi keys`, docs/case_file_reference.md).
#include <lagfsi/error.hpp>
#include <lagfsi/types.hpp>

#include <filesystem>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace lagfsi {

using Json = nlohmann::json;

/// One key of a case-file object: its name, its default (null: required) and a one-line description (SI
/// units, allowed values). A `derived` key's default is computed from other keys when the object is read
/// (Params::validate(const KeyTable&, const Json&)); `default_value` then only gives the JSON type, and the
/// description states the rule.
struct KeyDecl {
  std::string name;
  Json default_value;
  std::string doc;
  bool derived = false;
};

/// Marks a KeyDecl whose default depends on other keys: {"key", 0.0, "... (default: ...)", kDerived}.
inline constexpr bool kDerived = true;

/// The declaration of one kind of case-file object: a section (its JSON path, "*" for any array element, and
/// which variant in parentheses, e.g. "/bodies/* (type fluid)" or "/probes/* (fluid body, type pressure)"; a
/// section without a leading "/" is an object used in several places, e.g. "time function (type ramp)"), a
/// one-line description, and its keys. A table is constructed at namespace scope next to the code that reads
/// it; it registers itself in key_tables() for the reference.
class KeyTable {
 public:
  KeyTable(std::string section, std::string summary, std::vector<KeyDecl> keys);
  ~KeyTable();
  KeyTable(const KeyTable&) = delete;
  KeyTable& operator=(const KeyTable&) = delete;

  const std::string& section() const { return section_; }
  const std::string& summary() const { return summary_; }
  const std::vector<KeyDecl>& keys() const { return keys_; }
  /// The defaults object: every key with its default (null for required keys).
  Json defaults() const;

 private:
  std::string section_, summary_;
  std::vector<KeyDecl> keys_;
};

/// Every KeyTable of the program, in the reference's order (top level, analysis, output, bodies by type,
/// couplings, probes by body type, then the objects used in several places).
std::vector<const KeyTable*> key_tables();

/// The case-file reference in Markdown: one section per KeyTable with a table | key | default | description |.
std::string key_reference_markdown();

class Params {
 public:
  Params() = default;
  /// Owns `value`. Children returned by at() refer into the same document, so validate() on a child
  /// fills defaults into the whole document (which `lagfsi check` then prints resolved).
  Params(Json value, std::string file, std::string path = "")
      : owner_(std::make_shared<Json>(std::move(value))), file_(std::move(file)), path_(std::move(path)) {
    node_ = owner_.get();
  }

  /// Reads and parses a JSON file; a missing file or a syntax error throws InputError (with line).
  static Params load(const std::filesystem::path& file);

  /// Checks the keys and types of this object against `defaults` and fills the missing keys.
  /// Keys of `defaults` whose value is null are required. Number defaults accept integer or float
  /// values; object and array defaults are not descended into (validate children separately).
  void validate(const Json& defaults);
  /// The same with the defaults declared by `table`.
  void validate(const KeyTable& table);
  /// The same, with the defaults of `runtime_defaults` (keys of `table`, typically its derived keys)
  /// replacing the declared ones: for defaults computed from other keys when the object is read.
  void validate(const KeyTable& table, const Json& runtime_defaults);

  bool has(const std::string& key) const;
  Params at(const std::string& key) const;  ///< child object (error if absent)
  Params at(size_t i) const;                ///< array element
  size_t size() const;                      ///< array length (error if not an array)
  bool is_null() const { return node_->is_null(); }

  double number(const std::string& key) const;        ///< finite number
  double positive(const std::string& key) const;      ///< > 0
  double non_negative(const std::string& key) const;  ///< >= 0
  int integer(const std::string& key, int min_value = std::numeric_limits<int>::min()) const;
  bool boolean(const std::string& key) const;
  std::string string(const std::string& key) const;
  /// A name that becomes part of file names or a CSV column (cases, bodies, couplings, probes): 1-64 characters from
  /// letters, digits,
  /// '_', '-', '.' and '+', not starting with '.' (no paths, no hidden files, no '.' or '..').
  std::string identifier(const std::string& key) const;
  /// A string that must be one of `options` (error lists them).
  std::string choice(const std::string& key, const std::vector<std::string>& options) const;
  Vec2 vec2(const std::string& key) const;                 ///< [x, y], finite
  std::vector<Vec2> points(const std::string& key) const;  ///< [[x, y], ...]
  std::vector<double> numbers(const std::string& key) const;

  const Json& json() const { return *node_; }
  Json& json() { return *node_; }
  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }
  std::string child_path(const std::string& key) const { return path_ + "/" + key; }

  /// Throws InputError at this object's path (or at a child key's path).
  [[noreturn]] void fail(const std::string& reason) const;
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;

 private:
  Params(std::shared_ptr<Json> owner, Json* node, std::string file, std::string path)
      : owner_(std::move(owner)), node_(node), file_(std::move(file)), path_(std::move(path)) {}
  const Json& get(const std::string& key) const;
  std::shared_ptr<Json> owner_;
  Json* node_ = nullptr;
  std::string file_, path_;
};

/// Applies "a.b.0.c=value" to a JSON document: the value is parsed as JSON when it is valid JSON,
/// otherwise taken as a string; array indices are numbers; missing intermediate objects are created (the
/// case validation then rejects keys that do not exist). Throws InputError (file = "--set") for an array
/// index out of range or a path through a value that is not an object or array.
void apply_override(Json& doc, const std::string& assignment);

}  // namespace lagfsi
