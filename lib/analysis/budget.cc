// Error budget engine; method in budget.h.
#include "analysis/budget.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <random>
#include <sstream>

#include "analysis/stats.h"
#include "geo/angles.h"
#include "io/error.h"

namespace rk::analysis {

std::string BudgetUnitName(BudgetUnit unit) {
  switch (unit) {
    case BudgetUnit::kAngle:
      return "deg";
    case BudgetUnit::kPixel:
      return "px";
    case BudgetUnit::kLength:
      return "m";
  }
  return "?";
}

double BudgetToFile(BudgetUnit unit, double si) { return unit == BudgetUnit::kAngle ? geo::RadToDeg(si) : si; }

Eigen::VectorXd BudgetModel::NominalInputs() const {
  Eigen::VectorXd x(static_cast<Eigen::Index>(inputs_.size()));
  for (std::size_t i = 0; i < inputs_.size(); ++i) x(static_cast<Eigen::Index>(i)) = inputs_[i].nominal;
  return x;
}

const io::OptionTable<BudgetOptions>& BudgetOptions::Table() {
  static const io::OptionTable<BudgetOptions> table =
      io::OptionTable<BudgetOptions>()
          .Count("--samples", &BudgetOptions::samples, "", io::Bounds::Closed(0, 1e8),
                 "Monte Carlo draws (overrides the file; 0 = Jacobian only)")
          .Count("--seed", &BudgetOptions::seed, "", io::Bounds::Any(), "Monte Carlo seed (overrides the file)");
  return table;
}

namespace {

struct SigmaKey {
  const char* key;
  BudgetUnit unit;
  double to_si;
  const char* text;
};
constexpr SigmaKey kSigmaKeys[] = {
    {"deg", BudgetUnit::kAngle, M_PI / 180.0, "deg"},
    {"arcmin", BudgetUnit::kAngle, M_PI / 180.0 / 60.0, "arcmin"},
    {"arcsec", BudgetUnit::kAngle, M_PI / 180.0 / 3600.0, "arcsec"},
    {"rad", BudgetUnit::kAngle, 1.0, "rad"},
    {"px", BudgetUnit::kPixel, 1.0, "px"},
    {"m", BudgetUnit::kLength, 1.0, "m"},
    {"mm", BudgetUnit::kLength, 1e-3, "mm"},
};

std::string Fmt(double v, int prec = 6) {
  std::ostringstream s;
  s << std::setprecision(prec) << v;
  return s.str();
}

int FindInput(const BudgetModel& model, const std::string& name) {
  for (std::size_t i = 0; i < model.inputs().size(); ++i)
    if (model.inputs()[i].name == name) return static_cast<int>(i);
  return -1;
}

std::string Choices(const BudgetModel& model) {
  std::string s;
  for (const auto& g : model.groups()) s += (s.empty() ? "" : ", ") + g.first;
  for (const auto& q : model.inputs()) s += ", " + q.name;
  return s;
}

double Step(BudgetUnit unit) {
  switch (unit) {
    case BudgetUnit::kAngle:
      return 1e-7;
    case BudgetUnit::kPixel:
      return 1e-4;
    case BudgetUnit::kLength:
      return 1e-6;
  }
  return 1e-6;
}

}  // namespace

std::vector<BudgetSource> ParseBudgetSources(const io::Json& sources, const BudgetModel& model,
                                             const std::string& where) {
  if (!sources.is_array() || sources.empty())
    throw DataError(where, 0, 0, "\"sources\" must be a non-empty array of error sources");
  std::vector<BudgetSource> out;
  for (std::size_t k = 0; k < sources.size(); ++k) {
    const io::Json& j = sources[k];
    const std::string w = where + ": sources[" + std::to_string(k) + "]";
    if (!j.is_object()) throw DataError(where, 0, 0, w + " must be an object");
    BudgetSource s;
    s.name = j.contains("name") && j.at("name").is_string() ? j.at("name").get<std::string>() : "source " + std::to_string(k);
    // Inputs it applies to.
    if (!j.contains("applies_to")) throw DataError(where, 0, 0, w + ": missing \"applies_to\" (one of " + Choices(model) + ")");
    std::vector<std::string> names;
    if (j.at("applies_to").is_string()) {
      names.push_back(j.at("applies_to").get<std::string>());
    } else if (j.at("applies_to").is_array()) {
      for (const auto& n : j.at("applies_to")) {
        if (!n.is_string()) throw DataError(where, 0, 0, w + ": \"applies_to\" must hold names");
        names.push_back(n.get<std::string>());
      }
    } else {
      throw DataError(where, 0, 0, w + ": \"applies_to\" must be a name or a list of names");
    }
    for (const std::string& n : names) {
      bool found = false;
      for (const auto& g : model.groups()) {
        if (g.first == n) {
          s.inputs.insert(s.inputs.end(), g.second.begin(), g.second.end());
          found = true;
        }
      }
      const int i = FindInput(model, n);
      if (i >= 0) {
        s.inputs.push_back(i);
        found = true;
      }
      if (!found)
        throw DataError(where, 0, 0, w + ": unknown input '" + n + "' for model " + model.Name() + " (one of " +
                                         Choices(model) + ")");
    }
    std::sort(s.inputs.begin(), s.inputs.end());
    s.inputs.erase(std::unique(s.inputs.begin(), s.inputs.end()), s.inputs.end());
    // Distribution.
    std::string dist = "gaussian";
    if (j.contains("distribution")) {
      if (!j.at("distribution").is_string()) throw DataError(where, 0, 0, w + ": \"distribution\" must be a string");
      dist = j.at("distribution").get<std::string>();
    }
    if (dist == "gaussian") {
      s.distribution = BudgetDistribution::kGaussian;
    } else if (dist == "uniform") {
      s.distribution = BudgetDistribution::kUniform;
    } else {
      throw DataError(where, 0, 0, w + ": \"distribution\" must be gaussian or uniform, not '" + dist + "'");
    }
    // Exactly one σ (or uniform half width) key.
    int found = 0;
    for (const SigmaKey& sk : kSigmaKeys) {
      for (const char* prefix : {"sigma_", "half_width_"}) {
        const std::string key = std::string(prefix) + sk.key;
        if (!j.contains(key)) continue;
        const bool half = std::string(prefix) == "half_width_";
        if (half && s.distribution != BudgetDistribution::kUniform)
          throw DataError(where, 0, 0, w + ": \"" + key + "\" needs \"distribution\": \"uniform\"");
        if (!j.at(key).is_number()) throw DataError(where, 0, 0, w + ": \"" + key + "\" must be a number");
        const double v = j.at(key).get<double>();
        if (!(v >= 0.0) || !std::isfinite(v)) throw DataError(where, 0, 0, w + ": \"" + key + "\" must be >= 0");
        ++found;
        s.unit = sk.unit;
        s.sigma_si = v * sk.to_si / (half ? std::sqrt(3.0) : 1.0);
        s.given = (half ? "±" : "") + Fmt(v) + " " + sk.text;
      }
    }
    if (found != 1)
      throw DataError(where, 0, 0, w + ": give exactly one of sigma_deg, sigma_arcmin, sigma_arcsec, sigma_rad, "
                                       "sigma_px, sigma_m, sigma_mm (or half_width_<unit> with uniform)");
    for (int i : s.inputs) {
      const BudgetQuantity& q = model.inputs()[static_cast<std::size_t>(i)];
      if (q.unit != s.unit)
        throw DataError(where, 0, 0, w + ": a " + BudgetUnitName(s.unit) + " error cannot apply to input '" + q.name +
                                         "' (" + BudgetUnitName(q.unit) + ")");
    }
    out.push_back(s);
  }
  return out;
}

bool NumericalJacobian(const BudgetModel& model, const Eigen::VectorXd& x, Eigen::MatrixXd* J) {
  const auto n = x.size();
  const auto m = static_cast<Eigen::Index>(model.outputs().size());
  J->resize(m, n);
  Eigen::VectorXd yp, ym;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double h = Step(model.inputs()[static_cast<std::size_t>(i)].unit);
    Eigen::VectorXd xp = x, xm = x;
    xp(i) += h;
    xm(i) -= h;
    if (!model.Evaluate(xp, &yp) || !model.Evaluate(xm, &ym)) return false;
    for (Eigen::Index k = 0; k < m; ++k) {
      double dy = yp(k) - ym(k);
      if (model.outputs()[static_cast<std::size_t>(k)].wraps) dy = geo::WrapPi(dy);
      (*J)(k, i) = dy / (2.0 * h);
    }
  }
  return true;
}

BudgetResult RunBudget(const BudgetModel& model, const std::vector<BudgetSource>& sources,
                       const BudgetOptions& options) {
  std::string why;
  if (!options.Check(&why)) throw UsageError(why);
  const Eigen::VectorXd x0 = model.NominalInputs();
  const std::size_t n_in = model.inputs().size(), n_out = model.outputs().size();
  Eigen::VectorXd y0;
  if (!model.Evaluate(x0, &y0)) throw ProcessingError("the nominal computation of model " + model.Name() + " fails");
  BudgetResult r;
  r.jacobian = model.Jacobian();
  RK_CHECK(r.jacobian.rows() == static_cast<Eigen::Index>(n_out) && r.jacobian.cols() == static_cast<Eigen::Index>(n_in),
           "model Jacobian has the wrong shape");
  Eigen::MatrixXd Jn;
  if (NumericalJacobian(model, x0, &Jn)) {
    const double scale = std::max(1e-300, Jn.cwiseAbs().maxCoeff());
    r.jacobian_check_max_rel = (Jn - r.jacobian).cwiseAbs().maxCoeff() / scale;
  } else {
    r.jacobian_check_max_rel = std::nan("");
  }
  r.input_sigma.assign(n_in, 0.0);
  for (const BudgetSource& s : sources)
    for (int i : s.inputs) r.input_sigma[static_cast<std::size_t>(i)] += s.sigma_si * s.sigma_si;
  for (double& v : r.input_sigma) v = std::sqrt(v);
  r.outputs.resize(n_out);
  for (std::size_t k = 0; k < n_out; ++k) {
    BudgetOutputResult& o = r.outputs[k];
    o.nominal = y0(static_cast<Eigen::Index>(k));
    double total = 0.0;
    for (const BudgetSource& s : sources) {
      double v = 0.0;
      for (int i : s.inputs) {
        const double jk = r.jacobian(static_cast<Eigen::Index>(k), i);
        v += jk * jk;
      }
      const double share = s.sigma_si * std::sqrt(v);
      o.by_source.push_back(share);
      total += share * share;
    }
    o.sigma_jacobian = std::sqrt(total);
    o.sigma_mc = o.mean_mc = o.rms_mc = o.p95_abs_mc = std::nan("");
  }
  // Monte Carlo.
  r.samples = static_cast<std::int64_t>(options.samples);  // <= 1e8 (Check)
  if (r.samples > 0) {
    std::seed_seq seq{options.seed, static_cast<std::uint64_t>(0xB0D6E7)};
    std::mt19937_64 rng(seq);
    std::normal_distribution<double> normal(0.0, 1.0);
    std::uniform_real_distribution<double> uniform(-std::sqrt(3.0), std::sqrt(3.0));
    std::vector<std::vector<double>> errors(n_out);
    for (auto& e : errors) e.reserve(static_cast<std::size_t>(options.samples));
    Eigen::VectorXd x(x0.size()), y;
    for (std::int64_t s = 0; s < r.samples; ++s) {
      x = x0;
      for (const BudgetSource& src : sources) {
        for (int i : src.inputs) {
          const double z = src.distribution == BudgetDistribution::kGaussian ? normal(rng) : uniform(rng);
          x(i) += src.sigma_si * z;
        }
      }
      if (!model.Evaluate(x, &y)) {
        ++r.failed;
        continue;
      }
      for (std::size_t k = 0; k < n_out; ++k) {
        double d = y(static_cast<Eigen::Index>(k)) - y0(static_cast<Eigen::Index>(k));
        if (model.outputs()[k].wraps) d = geo::WrapPi(d);
        errors[k].push_back(d);
      }
    }
    for (std::size_t k = 0; k < n_out; ++k) {
      const auto st = ComputeErrorStats(errors[k]);
      if (!st) continue;
      BudgetOutputResult& o = r.outputs[k];
      o.sigma_mc = st->std;
      o.mean_mc = st->mean;
      o.rms_mc = st->rms;
      o.p95_abs_mc = st->p95_abs;
    }
  }
  return r;
}

namespace {

io::Json Num(double v) { return std::isfinite(v) ? io::Json(v) : io::Json(nullptr); }

}  // namespace

io::Json BudgetResultToJson(const BudgetModel& model, const std::vector<BudgetSource>& sources,
                            const BudgetOptions& options, const BudgetResult& r) {
  io::Json j;
  j["model"] = model.Name();
  j["description"] = model.Description();
  j["nominal"] = model.NominalJson();
  io::Json ins = io::Json::array();
  for (std::size_t i = 0; i < model.inputs().size(); ++i) {
    const BudgetQuantity& q = model.inputs()[i];
    io::Json e{{"name", q.name},
               {"unit", BudgetUnitName(q.unit)},
               {"nominal", BudgetToFile(q.unit, q.nominal)},
               {"sigma", BudgetToFile(q.unit, r.input_sigma[i])}};
    if (q.unit == BudgetUnit::kAngle) e["sigma_arcmin"] = geo::RadToDeg(r.input_sigma[i]) * 60.0;
    ins.push_back(e);
  }
  j["model_inputs"] = ins;
  io::Json src = io::Json::array();
  for (const BudgetSource& s : sources) {
    io::Json names = io::Json::array();
    for (int i : s.inputs) names.push_back(model.inputs()[static_cast<std::size_t>(i)].name);
    src.push_back({{"name", s.name},
                   {"given", s.given},
                   {"applies_to", names},
                   {"distribution", s.distribution == BudgetDistribution::kGaussian ? "gaussian" : "uniform"},
                   {"sigma", BudgetToFile(s.unit, s.sigma_si)},
                   {"unit", BudgetUnitName(s.unit)}});
  }
  j["sources"] = src;
  io::Json outs = io::Json::array();
  for (std::size_t k = 0; k < model.outputs().size(); ++k) {
    const BudgetQuantity& q = model.outputs()[k];
    const BudgetOutputResult& o = r.outputs[k];
    auto f = [&](double v) { return Num(BudgetToFile(q.unit, v)); };
    io::Json by = io::Json::object();
    for (std::size_t s = 0; s < sources.size(); ++s) by[sources[s].name] = f(o.by_source[s]);
    outs.push_back({{"name", q.name},
                    {"unit", BudgetUnitName(q.unit)},
                    {"nominal", f(o.nominal)},
                    {"sigma_jacobian", f(o.sigma_jacobian)},
                    {"sigma_monte_carlo", f(o.sigma_mc)},
                    {"mean_error_monte_carlo", f(o.mean_mc)},
                    {"rms_error_monte_carlo", f(o.rms_mc)},
                    {"p95_abs_error_monte_carlo", f(o.p95_abs_mc)},
                    {"sigma_jacobian_by_source", by}});
  }
  j["outputs"] = outs;
  io::Json jac = io::Json::array();
  for (Eigen::Index k = 0; k < r.jacobian.rows(); ++k) {
    io::Json row = io::Json::array();
    for (Eigen::Index i = 0; i < r.jacobian.cols(); ++i) row.push_back(r.jacobian(k, i));
    jac.push_back(row);
  }
  j["jacobian_si"] = {{"rows", io::Json::array()}, {"cols", io::Json::array()}, {"values", jac},
                      {"note", "d output / d input in SI units (rad, px, m); automatic differentiation"}};
  for (const auto& q : model.outputs()) j["jacobian_si"]["rows"].push_back(q.name);
  for (const auto& q : model.inputs()) j["jacobian_si"]["cols"].push_back(q.name);
  j["jacobian_check"] = {{"max_relative_difference_to_central_differences", Num(r.jacobian_check_max_rel)}};
  j["monte_carlo"] = {{"samples", r.samples}, {"failed", r.failed}, {"seed", options.seed},
                      {"sigma_standard_error_fraction", r.samples > 1 ? Num(1.0 / std::sqrt(2.0 * (r.samples - 1)))
                                                                       : io::Json(nullptr)}};
  return j;
}

std::string FormatBudgetTable(const BudgetModel& model, const std::vector<BudgetSource>& sources,
                              const BudgetResult& r) {
  std::ostringstream s;
  s << "model " << model.Name() << ": " << model.Description() << "\n";
  s << "inputs with errors (combined sigma):\n";
  for (std::size_t i = 0; i < model.inputs().size(); ++i) {
    if (r.input_sigma[i] == 0.0) continue;
    const BudgetQuantity& q = model.inputs()[i];
    s << "  " << std::left << std::setw(16) << q.name << std::right;
    if (q.unit == BudgetUnit::kAngle) {
      s << std::setw(12) << std::fixed << std::setprecision(4) << geo::RadToDeg(r.input_sigma[i]) * 60.0 << " arcmin\n";
    } else {
      s << std::setw(12) << std::fixed << std::setprecision(6) << r.input_sigma[i] << " " << BudgetUnitName(q.unit) << "\n";
    }
  }
  s << std::left << std::setw(12) << "output" << std::right << std::setw(6) << "unit" << std::setw(16) << "nominal"
    << std::setw(14) << "sigma_jac" << std::setw(14) << "sigma_mc" << std::setw(14) << "mean_mc";
  for (const BudgetSource& src : sources) s << "  " << std::setw(12) << src.name.substr(0, 12);
  s << "\n";
  for (std::size_t k = 0; k < model.outputs().size(); ++k) {
    const BudgetQuantity& q = model.outputs()[k];
    const BudgetOutputResult& o = r.outputs[k];
    auto f = [&](double v, int w, int p) {
      std::ostringstream t;
      if (std::isfinite(v)) {
        t << std::fixed << std::setprecision(p) << BudgetToFile(q.unit, v);
      } else {
        t << "-";
      }
      return std::string(static_cast<std::size_t>(std::max(0, w - static_cast<int>(t.str().size()))), ' ') + t.str();
    };
    s << std::left << std::setw(12) << q.name << std::right << std::setw(6) << BudgetUnitName(q.unit)
      << f(o.nominal, 16, 6) << f(o.sigma_jacobian, 14, 6) << f(o.sigma_mc, 14, 6) << f(o.mean_mc, 14, 6);
    for (std::size_t src = 0; src < sources.size(); ++src) s << "  " << f(o.by_source[src], 12, 6);
    s << "\n";
  }
  s << "Monte Carlo: " << r.samples << " draws, " << r.failed << " failed; autodiff vs central differences: max rel. "
    << std::scientific << std::setprecision(1) << r.jacobian_check_max_rel << "\n";
  return s.str();
}

}  // namespace rk::analysis

namespace rk::analysis {

io::RunSummary BudgetSummary(const BudgetModel& model, const BudgetResult& r) {
  io::RunSummary s;
  if (r.failed > 0) {
    s.Warn("draws_without_solution", std::to_string(r.failed) + " of " + std::to_string(r.samples) +
                                         " Monte Carlo draws had no solution and were left out");
  }
  if (!r.outputs.empty() && !std::isfinite(r.outputs[0].sigma_jacobian)) {
    s.Warn("singular_jacobian",
           "the Jacobian is singular at the nominal point (side-on view: a double root); only Monte "
           "Carlo sigmas are given");
  }
  for (std::size_t k = 0; k < r.outputs.size() && k < model.outputs().size(); ++k) {
    const BudgetQuantity& q = model.outputs()[k];
    s.AddFigure("sigma " + q.name, BudgetToFile(q.unit, r.outputs[k].sigma_jacobian), BudgetUnitName(q.unit));
  }
  return s;
}

}  // namespace rk::analysis
