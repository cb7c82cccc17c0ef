#include <lagfsi/input_file.hpp>
#include <lagfsi/params.hpp>
#include <lagfsi/text.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace lagfsi {

namespace {
std::string type_name(const Json& j) {
  if (j.is_null()) return "null";
  if (j.is_boolean()) return "a boolean";
  if (j.is_number()) return "a number";
  if (j.is_string()) return "a string";
  if (j.is_array()) return "an array";
  return "an object";
}

bool same_kind(const Json& value, const Json& def) {
  if (def.is_number()) return value.is_number();
  if (def.is_boolean()) return value.is_boolean();
  if (def.is_string()) return value.is_string();
  if (def.is_array()) return value.is_array();
  if (def.is_object()) return value.is_object();
  return true;
}

std::string v_str(double x) {
  std::ostringstream o;
  o << x;
  return o.str();
}

std::string join(const std::vector<std::string>& v) {
  std::string s;
  for (size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + v[i];
  return s;
}

/// Parser callback that rejects a key repeated in one object (nlohmann keeps the last silently, so a case
/// file with "dt" twice would run with whichever came last). Tracks the JSON path for the message.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(std::string file) : file_(std::move(file)) {}
  bool operator()(int /*depth*/, Json::parse_event_t event, Json& parsed) {
    switch (event) {
      case Json::parse_event_t::object_start:
        frames_.push_back({true, {}, "", 0});
        break;
      case Json::parse_event_t::array_start:
        frames_.push_back({false, {}, "", 0});
        break;
      case Json::parse_event_t::key: {
        Frame& f = frames_.back();
        const std::string k = parsed.get<std::string>();
        if (!f.keys.insert(k).second) throw InputError(file_, parent_path() + "/" + echo(k), "duplicate key");
        f.key = k;
        break;
      }
      case Json::parse_event_t::object_end:
      case Json::parse_event_t::array_end:
        frames_.pop_back();
        advance();
        break;
      case Json::parse_event_t::value:
        advance();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys;
    std::string key;  // objects: the key being read
    size_t index;     // arrays: the element being read
  };
  void advance() {
    if (!frames_.empty() && !frames_.back().object) ++frames_.back().index;
  }
  std::string parent_path() const {
    std::string path;
    for (size_t i = 0; i + 1 < frames_.size(); ++i)
      path += "/" + (frames_[i].object ? echo(frames_[i].key) : std::to_string(frames_[i].index));
    return path;
  }
  std::string file_;
  std::vector<Frame> frames_;
};

}  // namespace

Params Params::load(const std::filesystem::path& file) {
  std::string text;
  try {
    text = read_regular_file(file, kMaxCaseFileBytes);
  } catch (const InputFileError& e) {
    throw InputError(echo(file.string(), 200), "", e.what());
  }
  // Every string of the case ends up in resolved_case.json and in messages: it must be UTF-8 (the JSON
  // parser checks strings only; a byte in a comment would still reach an echo).
  size_t bad = 0;
  if (!valid_utf8(text, &bad))
    throw InputError(file.string(), "",
                     "not UTF-8 text: byte " + std::to_string(bad) + " (line " + std::to_string(line_of(text, bad)) +
                         ") is not valid UTF-8");
  try {
    DuplicateKeyCheck check(file.string());
    Json::parser_callback_t cb = [&check](int depth, Json::parse_event_t event, Json& parsed) {
      return check(depth, event, parsed);
    };
    return Params(Json::parse(text, cb, true, /*ignore_comments=*/true), file.string(), "");
  } catch (const Json::parse_error& e) {
    std::string what = e.what();
    const auto pos = what.find("syntax error");
    throw InputError(file.string(), "",
                     "invalid JSON at line " + std::to_string(line_of(text, e.byte)) + ": " +
                         (pos == std::string::npos ? what : what.substr(pos)));
  } catch (const Json::out_of_range& e) {
    // A number beyond double's range (1e999): nlohmann reports the literal, not its position.
    std::string what = e.what(), where;
    const auto q0 = what.find('\''), q1 = what.rfind('\'');
    if (q0 != std::string::npos && q1 > q0) {
      const std::string literal = what.substr(q0 + 1, q1 - q0 - 1);
      const auto at = text.find(literal);
      if (at != std::string::npos) where = " at line " + std::to_string(line_of(text, at));
      what = "number " + literal + " is out of range";
    }
    throw InputError(file.string(), "", "invalid JSON" + where + ": " + what);
  }
}

void Params::fail(const std::string& reason) const { throw InputError(file_, path_, reason); }
void Params::fail(const std::string& key, const std::string& reason) const {
  throw InputError(file_, path_ + "/" + echo(key), reason);
}

void Params::validate(const Json& defaults) {
  if (!(*node_).is_object()) fail("expected an object, found " + type_name((*node_)));
  std::vector<std::string> valid;
  for (const auto& [k, v] : defaults.items()) valid.push_back(k);
  for (const auto& [k, v] : (*node_).items()) {
    if (!defaults.contains(k)) fail(k, "unknown key (valid keys: " + join(valid) + ")");
    const Json& d = defaults.at(k);
    if (!d.is_null() && !same_kind(v, d)) fail(k, "expected " + type_name(d) + ", found " + type_name(v));
    if (v.is_number() && !std::isfinite(v.get<double>())) fail(k, "not a finite number");
  }
  for (const auto& [k, d] : defaults.items()) {
    if ((*node_).contains(k)) continue;
    if (d.is_null()) fail(k, "required key is missing");
    (*node_)[k] = d;
  }
}

void Params::validate(const KeyTable& table) { validate(table.defaults()); }

void Params::validate(const KeyTable& table, const Json& runtime_defaults) {
  Json defaults = table.defaults();
  for (const auto& [k, v] : runtime_defaults.items()) {
    // A default for a key the table does not declare would silently widen the valid keys: a program error.
    if (!defaults.contains(k)) throw std::logic_error("key '" + k + "' is not declared in '" + table.section() + "'");
    defaults[k] = v;
  }
  validate(defaults);
}

bool Params::has(const std::string& key) const {
  return (*node_).is_object() && (*node_).contains(key) && !(*node_).at(key).is_null();
}

const Json& Params::get(const std::string& key) const {
  if (!(*node_).is_object()) fail("expected an object, found " + type_name((*node_)));
  if (!(*node_).contains(key) || (*node_).at(key).is_null()) fail(key, "required key is missing");
  return (*node_).at(key);
}

Params Params::at(const std::string& key) const {
  get(key);
  return Params(owner_, &node_->at(key), file_, child_path(key));
}

Params Params::at(size_t i) const {
  if (!node_->is_array()) fail("expected an array, found " + type_name(*node_));
  if (i >= node_->size()) fail("index " + std::to_string(i) + " out of range");
  return Params(owner_, &node_->at(i), file_, path_ + "/" + std::to_string(i));
}

size_t Params::size() const {
  if (!(*node_).is_array()) fail("expected an array, found " + type_name((*node_)));
  return (*node_).size();
}

double Params::number(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_number()) fail(key, "expected a number, found " + type_name(v));
  const double x = v.get<double>();
  if (!std::isfinite(x)) fail(key, "not a finite number");
  return x;
}

double Params::positive(const std::string& key) const {
  const double x = number(key);
  if (!(x > 0.0)) fail(key, "must be positive (found " + v_str(x) + ")");
  return x;
}

double Params::non_negative(const std::string& key) const {
  const double x = number(key);
  if (x < 0.0) fail(key, "must not be negative (found " + v_str(x) + ")");
  return x;
}

int Params::integer(const std::string& key, int min_value) const {
  const Json& v = get(key);
  if (!v.is_number_integer()) fail(key, "expected an integer, found " + type_name(v));
  const long long x = v.get<long long>();
  if (x < min_value || x > std::numeric_limits<int>::max())
    fail(key, "must be an integer >= " + std::to_string(min_value) + " (found " + std::to_string(x) + ")");
  return static_cast<int>(x);
}

bool Params::boolean(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_boolean()) fail(key, "expected a boolean, found " + type_name(v));
  return v.get<bool>();
}

std::string Params::string(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_string()) fail(key, "expected a string, found " + type_name(v));
  return v.get<std::string>();
}

std::string Params::identifier(const std::string& key) const {
  const std::string s = string(key);
  const bool ok = !s.empty() && s.size() <= 64 && s[0] != '.' && std::all_of(s.begin(), s.end(), [](char ch) {
    const unsigned char u = static_cast<unsigned char>(ch);
    return std::isalnum(u) || ch == '_' || ch == '-' || ch == '.' || ch == '+';
  });
  if (!ok)
    fail(key,
         "must be 1-64 characters from letters, digits, '_', '-', '.' and '+', not starting with '.' (names "
         "become file names and CSV columns)");
  return s;
}

std::string Params::choice(const std::string& key, const std::vector<std::string>& options) const {
  const std::string s = string(key);
  for (const auto& o : options)
    if (o == s) return s;
  fail(key, "unknown value '" + echo(s) + "' (valid: " + join(options) + ")");
}

Vec2 Params::vec2(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number())
    fail(key, "expected [x, y] (two numbers)");
  Vec2 p(v[0].get<double>(), v[1].get<double>());
  if (!p.allFinite()) fail(key, "not finite");
  return p;
}

std::vector<Vec2> Params::points(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_array()) fail(key, "expected an array of [x, y] points");
  std::vector<Vec2> out;
  for (size_t i = 0; i < v.size(); ++i) {
    const Json& p = v[i];
    if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number())
      fail(key + "/" + std::to_string(i), "expected [x, y] (two numbers)");
    Vec2 q(p[0].get<double>(), p[1].get<double>());
    if (!q.allFinite()) fail(key + "/" + std::to_string(i), "not finite");
    out.push_back(q);
  }
  return out;
}

std::vector<double> Params::numbers(const std::string& key) const {
  const Json& v = get(key);
  if (!v.is_array()) fail(key, "expected an array of numbers");
  std::vector<double> out;
  for (size_t i = 0; i < v.size(); ++i) {
    if (!v[i].is_number() || !std::isfinite(v[i].get<double>()))
      fail(key + "/" + std::to_string(i), "expected a finite number");
    out.push_back(v[i].get<double>());
  }
  return out;
}

void apply_override(Json& doc, const std::string& assignment) {
  size_t bad = 0;
  if (!valid_utf8(assignment, &bad))
    throw InputError("--set", echo(assignment), "not UTF-8 text (byte " + std::to_string(bad) + ")");
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) throw InputError("--set", echo(assignment), "expected key.path=value");
  const std::string key = assignment.substr(0, eq), text = assignment.substr(eq + 1);
  Json value;
  try {
    value = Json::parse(text);
  } catch (const Json::parse_error&) {
    value = text;
  } catch (const Json::out_of_range&) {
    std::string where = "/" + key;
    std::replace(where.begin(), where.end(), '.', '/');
    throw InputError("--set", echo(where), "number " + echo(text) + " is out of range");
  }
  Json* node = &doc;
  std::string path;
  std::stringstream ss(key);
  std::string part;
  std::vector<std::string> parts;
  while (std::getline(ss, part, '.')) parts.push_back(part);
  for (size_t i = 0; i < parts.size(); ++i) {
    const std::string& p = parts[i];
    path += '/';  // (not "/" + echo(p): a false -Wrestrict of GCC 12, bug 105329)
    path += echo(p);
    if (node->is_array()) {
      size_t idx = 0;
      const bool digits = !p.empty() && p.size() < 10 &&
                          std::all_of(p.begin(), p.end(), [](char ch) { return ch >= '0' && ch <= '9'; });
      if (!digits) throw InputError("--set", path, "expected an array index");
      idx = std::stoul(p);
      if (idx >= node->size()) throw InputError("--set", path, "array index out of range");
      node = &(*node)[idx];
    } else if (node->is_object()) {
      // A missing intermediate object is created (the case validation then checks the key).
      node = &(*node)[p];
    } else if (node->is_null()) {
      *node = Json::object();
      node = &(*node)[p];
    } else {
      throw InputError("--set", path, "cannot descend into a value that is not an object or array");
    }
  }
  *node = value;
}

}  // namespace lagfsi
