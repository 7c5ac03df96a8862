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
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "io/json_util.h"

namespace rk::io {

// Valid values of a number option: lo < x (lo_open) or lo <= x, and x < hi or x <= hi. Every bound
// also requires a finite value unless the bound itself is infinite on that side; Finite() refuses
// infinity on an unbounded side too (an option whose infinite value would make no sense).
struct Bounds {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool finite = false;  // ±inf refused even on an unbounded side (Finite())

  static Bounds Any() { return {}; }
  static Bounds Positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Bounds AtLeast(double lo) { return {lo, std::numeric_limits<double>::infinity(), false, false}; }
  static Bounds Closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Bounds Open(double lo, double hi) { return {lo, hi, true, true}; }
  static Bounds LeftOpen(double lo, double hi) { return {lo, hi, true, false}; }
  static Bounds RightOpen(double lo, double hi) { return {lo, hi, false, true}; }
  // The same bounds, with ±infinity refused on an unbounded side too ("finite and > 0").
  Bounds Finite() const {
    Bounds b = *this;
    b.finite = true;
    return b;
  }

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
  enum class Kind { kReal, kInteger, kCount, kFlag, kChoice };
  Kind kind = Kind::kReal;
  std::string flag;  // "--turret-max-gap"; CLI11 aliases go in `names` ("-k,--keep-going")
  std::string unit;  // "s", "px", "samples per side": in messages; a short unit also in the report key
  std::string help;  // --help text (CLI11 adds the type and the default)
  Bounds bounds;
  // The member, reached through the Options struct (a nested struct's member too, see Sub()).
  std::function<double&(O&)> real;                // kReal
  std::function<int&(O&)> integer;                // kInteger
  std::function<std::uint64_t&(O&)> count;        // kCount: seeds, sizes
  std::function<bool&(O&)> flag_value;            // kFlag: a switch without a value
  std::vector<std::string> choices;               // kChoice: the names, in --help order
  std::function<std::string(const O&)> get_choice;          // kChoice: current value's name
  std::function<bool(O*, const std::string&)> set_choice;  // kChoice: false for an unknown name
  std::string aliases;  // extra CLI11 names, e.g. "-k" (none in the report key or messages)

  std::string key() const { return ReportKey(flag, unit); }
  std::string names() const { return aliases.empty() ? flag : aliases + "," + flag; }
  double number(const O& o) const {
    O& m = const_cast<O&>(o);  // the accessors only read here
    switch (kind) {
      case Kind::kReal:
        return real(m);
      case Kind::kInteger:
        return static_cast<double>(integer(m));
      case Kind::kCount:
        return static_cast<double>(count(m));
      default:
        return 0.0;
    }
  }
};

// The options of one Options struct, in --help order.
template <class O>
class OptionTable {
 public:
  OptionTable& Real(std::string flag, double O::*member, std::string unit, Bounds bounds, std::string help) {
    return Real(std::move(flag), Member(member), std::move(unit), bounds, std::move(help));
  }
  OptionTable& Real(std::string flag, std::function<double&(O&)> ref, std::string unit, Bounds bounds,
                    std::string help) {
    OptionSpec<O> s = Spec(OptionSpec<O>::Kind::kReal, std::move(flag), std::move(unit), bounds, std::move(help));
    s.real = std::move(ref);
    return Add(std::move(s));
  }
  OptionTable& Integer(std::string flag, int O::*member, std::string unit, Bounds bounds, std::string help) {
    return Integer(std::move(flag), Member(member), std::move(unit), bounds, std::move(help));
  }
  OptionTable& Integer(std::string flag, std::function<int&(O&)> ref, std::string unit, Bounds bounds,
                       std::string help) {
    OptionSpec<O> s = Spec(OptionSpec<O>::Kind::kInteger, std::move(flag), std::move(unit), bounds, std::move(help));
    s.integer = std::move(ref);
    return Add(std::move(s));
  }
  // A std::uint64_t member (a seed, a count of bytes). Bounds are checked as doubles.
  OptionTable& Count(std::string flag, std::uint64_t O::*member, std::string unit, Bounds bounds, std::string help) {
    OptionSpec<O> s = Spec(OptionSpec<O>::Kind::kCount, std::move(flag), std::move(unit), bounds, std::move(help));
    s.count = Member(member);
    return Add(std::move(s));
  }
  // A switch: present = true. In the report as true/false.
  OptionTable& Flag(std::string flag, bool O::*member, std::string help) {
    OptionSpec<O> s = Spec(OptionSpec<O>::Kind::kFlag, std::move(flag), "", Bounds::Any(), std::move(help));
    s.flag_value = Member(member);
    return Add(std::move(s));
  }
  // An enumeration member E, with a name for each value: `names` is {{value, "name"}, ...}.
  template <class E>
  OptionTable& Choice(std::string flag, E O::*member, std::vector<std::pair<E, std::string>> names, std::string help) {
    OptionSpec<O> s = Spec(OptionSpec<O>::Kind::kChoice, std::move(flag), "", Bounds::Any(), std::move(help));
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
    return Add(std::move(s));
  }

  // The same, with the names given by the enumeration's own name function (one owner of the names).
  template <class E>
  OptionTable& Choice(std::string flag, E O::*member, const std::vector<E>& values, std::string (*name)(E),
                      std::string help) {
    std::vector<std::pair<E, std::string>> names;
    for (E v : values) names.emplace_back(v, name(v));
    return Choice(std::move(flag), member, std::move(names), std::move(help));
  }

  // Every option of `inner`, the table of a nested Options struct `O::*member` (a simulator's trajectory
  // options inside its scenario options): one table per struct, composed as the structs are.
  template <class I>
  OptionTable& Sub(I O::*member, const OptionTable<I>& inner) {
    for (const auto& is : inner.specs()) {
      OptionSpec<O> s;
      s.kind = static_cast<typename OptionSpec<O>::Kind>(is.kind);
      s.flag = is.flag, s.unit = is.unit, s.help = is.help, s.bounds = is.bounds, s.aliases = is.aliases;
      s.choices = is.choices;
      if (is.real) s.real = [member, f = is.real](O& o) -> double& { return f(o.*member); };
      if (is.integer) s.integer = [member, f = is.integer](O& o) -> int& { return f(o.*member); };
      if (is.count) s.count = [member, f = is.count](O& o) -> std::uint64_t& { return f(o.*member); };
      if (is.flag_value) s.flag_value = [member, f = is.flag_value](O& o) -> bool& { return f(o.*member); };
      if (is.get_choice) s.get_choice = [member, f = is.get_choice](const O& o) { return f(o.*member); };
      if (is.set_choice) s.set_choice = [member, f = is.set_choice](O* o, const std::string& v) { return f(&(o->*member), v); };
      Add(std::move(s));
    }
    return *this;
  }

  // Extra CLI11 names for the option added last ("-k" for --keep-going).
  OptionTable& Alias(std::string aliases) {
    specs_.back().aliases = std::move(aliases);
    return *this;
  }

  // False with "--flag must be ... unit" for the first option outside its bounds.
  bool Check(const O& o, std::string* why) const {
    for (const auto& s : specs_) {
      if (!Bounded(s) || s.bounds.Contains(s.number(o))) continue;
      if (why) *why = s.flag + " must be " + s.bounds.Describe() + (s.unit.empty() ? "" : " " + s.unit);
      return false;
    }
    return true;
  }

  // {"report_key": value, ...}: the report's "options" block.
  Json ToJson(const O& o) const {
    Json j = Json::object();
    O& m = const_cast<O&>(o);  // the accessors only read here
    for (const auto& s : specs_) {
      switch (s.kind) {
        case OptionSpec<O>::Kind::kReal:
          j[s.key()] = s.real(m);
          break;
        case OptionSpec<O>::Kind::kInteger:
          j[s.key()] = s.integer(m);
          break;
        case OptionSpec<O>::Kind::kCount:
          j[s.key()] = s.count(m);
          break;
        case OptionSpec<O>::Kind::kFlag:
          j[s.key()] = s.flag_value(m);
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
  template <class T>
  static std::function<T&(O&)> Member(T O::*member) {
    return [member](O& o) -> T& { return o.*member; };
  }
  static OptionSpec<O> Spec(typename OptionSpec<O>::Kind kind, std::string flag, std::string unit, Bounds bounds,
                            std::string help) {
    OptionSpec<O> s;
    s.kind = kind;
    s.flag = std::move(flag), s.unit = std::move(unit), s.help = std::move(help), s.bounds = bounds;
    return s;
  }
  static bool Bounded(const OptionSpec<O>& s) {
    using Kind = typename OptionSpec<O>::Kind;
    return s.kind == Kind::kReal || s.kind == Kind::kInteger || s.kind == Kind::kCount;
  }
  OptionTable& Add(OptionSpec<O> s) {
    specs_.push_back(std::move(s));
    return *this;
  }

  std::vector<OptionSpec<O>> specs_;
};

}  // namespace rk::io
