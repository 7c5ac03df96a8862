// Tool options described once (docs/architecture.md "Adding an option").
//
// An option has a command-line flag, a member of the library's Options struct, a unit, a valid range
// and a help text. Before, each was written in three to five places: the flag in the app, the member,
// a Check() message naming the flag, the report key, rk-run's lists. An OptionTable<Options> holds
// one OptionSpec per option, next to the struct in the library, and everything else comes from it:
//   - OptionTable::Check   the valid ranges, with one message form "--flag must be > 0 s";
//   - OptionTable::ToJson  the report's "options" block, keys from the flag and unit (ReportKey);
//   - cli::AddOptions      the CLI11 registration (io/cli.h; only apps include CLI11).
// The pattern is COLMAP's OptionManager (src/colmap/controllers/option_manager.h): register once,
// read everywhere. Options that are not a bounded number or a choice (paths, lists, cross-option
// rules) stay in the app or in a hand-written part of Check().
#pragma once

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/json_util.h"

namespace rk::io {

// Valid values of a number option: lo < x (lo_open) or lo <= x, and x < hi or x <= hi. Every bound
// also requires a finite value unless the bound itself is infinite on that side.
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;

  static Bounds Any() { return {}; }
  static Bounds Positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Bounds AtLeast(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
  static Bounds Closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Bounds Open(double lo, double hi) { return {lo, hi, true, true}; }
  static Bounds LeftOpen(double lo, double hi) { return {lo, hi, true, false}; }
  static Bounds RightOpen(double lo, double hi) { return {lo, hi, false, true}; }

  bool Contains(double x) const;
  // "> 0", ">= 1", "in [2, 50]", "in (0, 0.5]", "<= 3" (numbers as %g).
  std::string Describe() const;
};

// Report key of an option: the flag without its dashes, '-' → '_', and the unit appended when it is a
// unit a member name carries ("s", "px", "m", "deg", "hz", "dn", "mm", "arcsec") and the name does not
// already end with it: --turret-max-gap [s] → turret_max_gap_s, --range-window → range_window.
std::string ReportKey(const std::string& flag, const std::string& unit);

template <class O>
struct OptionSpec {
  enum class Kind { kReal, kInteger, kChoice };
  Kind kind = Kind::kReal;
  std::string flag;  // "--turret-max-gap"
  std::string unit;  // "s", "px", "samples per side": in messages; a short unit also in the report key
  std::string help;  // --help text (CLI11 adds the type and the default)
  Bounds bounds;
  double O::*real = nullptr;
  int O::*integer = nullptr;
  std::vector<std::string> choices;                         // kChoice: the names, in --help order
  std::function<std::string(const O&)> get_choice;          // kChoice: current value's name
  std::function<bool(O*, const std::string&)> set_choice;  // kChoice: false for an unknown name

  std::string key() const { return ReportKey(flag, unit); }
  double number(const O& o) const { return kind == Kind::kReal ? o.*real : static_cast<double>(o.*integer); }
};

// The options of one Options struct, in --help order.
template <class O>
class OptionTable {
 public:
  OptionTable& Real(std::string flag, double O::*member, std::string unit, Bounds bounds, std::string help) {
    OptionSpec<O> s;
    s.kind = OptionSpec<O>::Kind::kReal;
    s.flag = std::move(flag), s.unit = std::move(unit), s.help = std::move(help), s.bounds = bounds;
    s.real = member;
    specs_.push_back(std::move(s));
    return *this;
  }
  OptionTable& Integer(std::string flag, int O::*member, std::string unit, Bounds bounds, std::string help) {
    OptionSpec<O> s;
    s.kind = OptionSpec<O>::Kind::kInteger;
    s.flag = std::move(flag), s.unit = std::move(unit), s.help = std::move(help), s.bounds = bounds;
    s.integer = member;
    specs_.push_back(std::move(s));
    return *this;
  }
  // An enumeration member E, with a name for each value: `names` is {{value, "name"}, ...}.
  template <class E>
  OptionTable& Choice(std::string flag, E O::*member, std::vector<std::pair<E, std::string>> names, std::string help) {
    OptionSpec<O> s;
    s.kind = OptionSpec<O>::Kind::kChoice;
    s.flag = std::move(flag), s.help = std::move(help);
    for (const auto& n : names) s.choices.push_back(n.second);
    s.get_choice = [member, names](const O& o) {
      for (const auto& n : names) {
        if (o.*member == n.first) return n.second;
      }
      return std::string();
    };
    s.set_choice = [member, names](O* o, const std::string& name) {
      for (const auto& n : names) {
        if (n.second == name) {
          o->*member = n.first;
          return true;
        }
      }
      return false;
    };
    specs_.push_back(std::move(s));
    return *this;
  }

  // The same, with the names given by the enumeration's own name function (one owner of the names).
  template <class E>
  OptionTable& Choice(std::string flag, E O::*member, const std::vector<E>& values, std::string (*name)(E),
                      std::string help) {
    std::vector<std::pair<E, std::string>> names;
    for (E v : values) names.emplace_back(v, name(v));
    return Choice(std::move(flag), member, std::move(names), std::move(help));
  }

  // False with "--flag must be ... unit" for the first option outside its bounds.
  bool Check(const O& o, std::string* why) const {
    for (const auto& s : specs_) {
      if (s.kind == OptionSpec<O>::Kind::kChoice || s.bounds.Contains(s.number(o))) continue;
      if (why) *why = s.flag + " must be " + s.bounds.Describe() + (s.unit.empty() ? "" : " " + s.unit);
      return false;
    }
    return true;
  }

  // {"report_key": value, ...}: the report's "options" block.
  Json ToJson(const O& o) const {
    Json j = Json::object();
    for (const auto& s : specs_) {
      switch (s.kind) {
        case OptionSpec<O>::Kind::kReal:
          j[s.key()] = o.*s.real;
          break;
        case OptionSpec<O>::Kind::kInteger:
          j[s.key()] = o.*s.integer;
          break;
        case OptionSpec<O>::Kind::kChoice:
          j[s.key()] = s.get_choice(o);
          break;
      }
    }
    return j;
  }

  const std::vector<OptionSpec<O>>& specs() const { return specs_; }
  const OptionSpec<O>* Find(const std::string& flag) const {
    for (const auto& s : specs_) {
      if (s.flag == flag) return &s;
    }
    return nullptr;
  }

 private:
  std::vector<OptionSpec<O>> specs_;
};

}  // namespace rk::io
