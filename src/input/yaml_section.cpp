#include "input/yaml_section.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace periadapt {

Section::Section(YAML::Node node, std::string path, std::string file)
    : node_(std::move(node)), path_(std::move(path)), file_(std::move(file)) {}

std::string Section::key_path(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void Section::fail(const std::string& key, const std::string& message) const {
  YAML::Node n = (!key.empty() && node_.IsMap() && node_[key]) ? node_[key] : node_;
  fail_at(n, key, message);
}

void Section::fail_at(const YAML::Node& n, const std::string& key,
                      const std::string& message) const {
  const YAML::Mark m = n.Mark();
  const int line = m.line >= 0 ? m.line + 1 : 0;
  const int col = m.column >= 0 ? m.column + 1 : 0;
  throw DeckError(file_, line, col, key.empty() ? path_ : key_path(key), message);
}

DeckPlace Section::place(const std::string& key) const {
  const YAML::Node n = (!key.empty() && node_.IsMap() && node_[key]) ? node_[key] : node_;
  const YAML::Mark m = n.Mark();
  return {key.empty() ? path_ : key_path(key), m.line >= 0 ? m.line + 1 : 0,
          m.column >= 0 ? m.column + 1 : 0};
}

bool Section::has(const std::string& key) const {
  read_.insert(key);  // asking for a key makes it a known key of this section
  return node_.IsMap() && node_[key] && !node_[key].IsNull();
}

void Section::missing(const std::string& key, const std::string& what) const {
  if (node_.IsMap()) {
    for (const auto& kv : node_) {
      if (!kv.first.IsScalar())
        fail_at(kv.first, "", "a key must be a plain name, not a list, mapping or empty key");
      const std::string k = kv.first.as<std::string>();
      if (read_.count(k)) continue;
      if (edit_distance(k, key) <= std::max<std::size_t>(2, key.size() / 3))
        fail_at(kv.first, k, "unknown key; did you mean '" + key + "'?");
    }
  }
  fail(key, what);
}

YAML::Node Section::get(const std::string& key) const {
  read_.insert(key);
  if (!node_.IsMap()) return YAML::Node();
  return node_[key];
}

static std::string describe(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "nothing";
}

double Section::number(const std::string& key, std::optional<double> fallback,
                       const std::function<std::string(double)>& check) {
  YAML::Node n = get(key);
  if (!n || n.IsNull()) {
    if (!fallback) missing(key, "missing required number");
    return *fallback;
  }
  double v;
  try {
    if (!n.IsScalar()) throw YAML::BadConversion(n.Mark());
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    fail(key, "expected a number, got " + describe(n));
  }
  if (!std::isfinite(v)) fail(key, "expected a finite number, got " + describe(n));
  if (check) {
    std::string err = check(v);
    if (!err.empty()) fail(key, err + " (got " + n.Scalar() + ")");
  }
  return v;
}

long Section::integer(const std::string& key, std::optional<long> fallback,
                      const std::function<std::string(long)>& check) {
  YAML::Node n = get(key);
  if (!n || n.IsNull()) {
    if (!fallback) missing(key, "missing required integer");
    return *fallback;
  }
  long v;
  try {
    if (!n.IsScalar()) throw YAML::BadConversion(n.Mark());
    v = n.as<long>();
  } catch (const YAML::Exception&) {
    fail(key, "expected an integer, got " + describe(n));
  }
  if (check) {
    std::string err = check(v);
    if (!err.empty()) fail(key, err + " (got " + n.Scalar() + ")");
  }
  return v;
}

bool Section::boolean(const std::string& key, std::optional<bool> fallback) {
  YAML::Node n = get(key);
  if (!n || n.IsNull()) {
    if (!fallback) missing(key, "missing required true/false");
    return *fallback;
  }
  try {
    if (!n.IsScalar()) throw YAML::BadConversion(n.Mark());
    return n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false, got " + describe(n));
  }
}

std::string Section::text(const std::string& key, std::optional<std::string> fallback) {
  YAML::Node n = get(key);
  if (!n || n.IsNull()) {
    if (!fallback) missing(key, "missing required value");
    return *fallback;
  }
  if (!n.IsScalar()) fail(key, "expected a single value, got " + describe(n));
  return n.Scalar();
}

std::string Section::choice(const std::string& key, const std::vector<std::string>& allowed,
                            std::optional<std::string> fallback) {
  std::string v = text(key, fallback);
  if (std::find(allowed.begin(), allowed.end(), v) != allowed.end()) return v;
  std::string list;
  for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
  fail(key, "'" + v + "' is not allowed; allowed: " + list);
}

std::vector<double> Section::numbers(const std::string& key, std::size_t min_len,
                                     std::size_t max_len) {
  YAML::Node n = get(key);
  if (!n || n.IsNull()) missing(key, "missing required list of numbers");
  std::vector<double> out;
  if (n.IsScalar() && min_len <= 1) {
    out.push_back(number(key));
    return out;
  }
  if (!n.IsSequence()) fail(key, "expected a list of numbers, got " + describe(n));
  for (const auto& e : n) {
    try {
      if (!e.IsScalar()) throw YAML::BadConversion(e.Mark());
      out.push_back(e.as<double>());
    } catch (const YAML::Exception&) {
      fail_at(e, key, "expected a number, got " + describe(e));
    }
    if (!std::isfinite(out.back())) fail_at(e, key, "expected a finite number");
  }
  if (out.size() < min_len || out.size() > max_len) {
    std::ostringstream os;
    os << "expected " << min_len;
    if (max_len != min_len) os << " to " << max_len;
    os << " numbers, got " << out.size();
    fail(key, os.str());
  }
  return out;
}

std::vector<std::vector<double>> Section::points(const std::string& key, std::size_t count,
                                                 std::size_t dim) {
  YAML::Node n = get(key);
  if (!n || !n.IsSequence() || n.size() != count)
    fail(key, "expected a list of " + std::to_string(count) + " points, each [" +
                  std::string(dim == 1 ? "x" : dim == 2 ? "x, y" : "x, y, z") + "]");
  std::vector<std::vector<double>> out;
  for (const auto& p : n) {
    if (!p.IsSequence() || p.size() != dim)
      fail_at(p, key, "each point needs " + std::to_string(dim) + " coordinates");
    std::vector<double> q;
    for (const auto& e : p) {
      try {
        if (!e.IsScalar()) throw YAML::BadConversion(e.Mark());
        q.push_back(e.as<double>());
      } catch (const YAML::Exception&) {
        fail_at(e, key, "expected a number, got " + describe(e));
      }
      if (!std::isfinite(q.back())) fail_at(e, key, "expected a finite coordinate, got " + describe(e));
    }
    out.push_back(q);
  }
  return out;
}

Section Section::section(const std::string& key) {
  YAML::Node n = get(key);
  if (!n || n.IsNull()) missing(key, "missing required section");
  if (!n.IsMap()) fail(key, "expected a mapping of keys, got " + describe(n));
  return Section(n, key_path(key), file_);
}

std::optional<Section> Section::optional_section(const std::string& key) {
  YAML::Node n = get(key);
  if (!n || n.IsNull()) return std::nullopt;
  if (!n.IsMap()) fail(key, "expected a mapping of keys, got " + describe(n));
  return Section(n, key_path(key), file_);
}

std::vector<Section> Section::list(const std::string& key) {
  YAML::Node n = get(key);
  std::vector<Section> out;
  if (!n || n.IsNull()) return out;
  if (!n.IsSequence()) fail(key, "expected a list, got " + describe(n));
  std::size_t k = 0;
  for (const auto& e : n) {
    const std::string p = key_path(key) + "[" + std::to_string(k++) + "]";
    if (!e.IsMap()) {
      Section tmp(e, p, file_);
      tmp.fail_at(e, "", "expected a mapping of keys, got " + describe(e));
    }
    out.emplace_back(e, p, file_);
  }
  return out;
}

YAML::Node Section::raw(const std::string& key) { return get(key); }

void Section::finish() const {
  if (!node_.IsMap()) return;
  std::vector<std::string> known(read_.begin(), read_.end());
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar())
      fail_at(kv.first, "", "a key must be a plain name, not a list, mapping or empty key");
    const std::string k = kv.first.as<std::string>();
    if (read_.count(k)) continue;
    std::string best;
    std::size_t bd = 1000;
    for (const auto& c : known) {
      std::size_t d = edit_distance(k, c);
      if (d < bd) {
        bd = d;
        best = c;
      }
    }
    std::string msg = "unknown key";
    if (!best.empty() && bd <= std::max<std::size_t>(2, k.size() / 3))
      msg += "; did you mean '" + best + "'?";
    std::string list;
    for (const auto& c : known) list += (list.empty() ? "" : ", ") + c;
    msg += (msg.back() == '?' ? " " : ". ") + std::string("Allowed here: ") + list;
    fail_at(kv.first, k, msg);
  }
}

std::function<std::string(double)> positive() {
  return [](double v) { return v > 0 ? std::string() : std::string("must be > 0"); };
}
std::function<std::string(double)> non_negative() {
  return [](double v) { return v >= 0 ? std::string() : std::string("must be >= 0"); };
}
std::function<std::string(double)> at_least(double lo) {
  return [lo](double v) {
    std::ostringstream os;
    os << "must be >= " << lo;
    return v >= lo ? std::string() : os.str();
  };
}
std::function<std::string(double)> in_range(double lo, double hi) {
  return [lo, hi](double v) {
    std::ostringstream os;
    os << "must be in [" << lo << ", " << hi << "]";
    return (v >= lo && v <= hi) ? std::string() : os.str();
  };
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace periadapt
