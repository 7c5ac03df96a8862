// Error budget (rk-analyze budget): propagation of independent error sources through a computation,
// by Jacobian (first order, derivatives by automatic differentiation) and by Monte Carlo (the full
// nonlinear computation), side by side. Seed 004 §4 does the first by hand (eqs. 6–9); here any model that
// implements BudgetModel gets both.
//
// Model. y = g(x): inputs x (SI, radians) with nominal values x0, outputs y (SI). A source s adds an error
// e_s,i to each input i it applies to, independently per input, with standard deviation σ_s (Gaussian, or
// uniform on ±σ_s·√3). Combined input σ_i = sqrt(Σ_s σ_s,i²) (for the theodolite angles of seed 004 this is
// the RSS 5.215′ of §4.1).
// Jacobian σ: J = ∂g/∂x at x0; each source's share σ_s(y_k) = σ_s · sqrt(Σ_{i∈s} J_ki²); total
//   σ(y_k) = sqrt(Σ_s σ_s(y_k)²) = sqrt(Σ_i J_ki² σ_i²).
// Monte Carlo: N draws of all sources, y = g(x0 + e); errors Δy = y − g(x0) (angle outputs wrapped to
// (−π, π]); σ = sample standard deviation, plus mean, RMS and the 95th percentile of |Δy|. A draw whose
// computation fails (no solution) is counted, not used. The MC standard error of σ is ≈ σ / sqrt(2 (N − 1)).
// The autodiff Jacobian is also compared with central differences (steps 1e-7 rad, 1e-4 px, 1e-6 m): the
// largest relative difference is reported as a check.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/json_util.h"
#include "io/options.h"
#include "io/run_summary.h"

namespace rk::analysis {

// Unit family of a model quantity: how σ keys in the budget file are converted and checked.
enum class BudgetUnit { kAngle, kPixel, kLength };

struct BudgetQuantity {
  std::string name;        // "boresight_az", "nose_x", "length", "yaw", ...
  BudgetUnit unit = BudgetUnit::kLength;
  double nominal = 0.0;    // SI (rad, px, m)
  bool wraps = false;      // an azimuth-like angle: differences wrapped to (−π, π]
};

// File units: deg for angles, px, m.
std::string BudgetUnitName(BudgetUnit unit);
double BudgetToFile(BudgetUnit unit, double si);

class BudgetModel {
 public:
  virtual ~BudgetModel() = default;
  virtual std::string Name() const = 0;
  virtual std::string Description() const = 0;
  const std::vector<BudgetQuantity>& inputs() const { return inputs_; }
  const std::vector<BudgetQuantity>& outputs() const { return outputs_; }
  // Named groups of inputs a source may apply to (besides single input names).
  const std::vector<std::pair<std::string, std::vector<int>>>& groups() const { return groups_; }
  // y = g(x) (SI). False when the computation fails (e.g. no solution).
  virtual bool Evaluate(const Eigen::VectorXd& x, Eigen::VectorXd* y) const = 0;
  // ∂g/∂x at the nominal inputs, by automatic differentiation (outputs × inputs).
  virtual Eigen::MatrixXd Jacobian() const = 0;
  // Extra description of the nominal geometry for the report (optional).
  virtual io::Json NominalJson() const { return io::Json::object(); }

  Eigen::VectorXd NominalInputs() const;

 protected:
  std::vector<BudgetQuantity> inputs_, outputs_;
  std::vector<std::pair<std::string, std::vector<int>>> groups_;
};

enum class BudgetDistribution { kGaussian, kUniform };

struct BudgetSource {
  std::string name;
  std::vector<int> inputs;  // indices into model.inputs()
  BudgetUnit unit = BudgetUnit::kAngle;
  double sigma_si = 0.0;    // standard deviation (rad, px or m), >= 0
  BudgetDistribution distribution = BudgetDistribution::kGaussian;
  std::string given;        // how the file stated it, e.g. "5 arcmin" (for the report)
};

// Parses the "sources" array of a budget file against a model:
//   {"name": "crosshair", "applies_to": "boresight" | "boresight_az" | [..], "sigma_arcmin": 5,
//    "distribution": "gaussian" | "uniform"}
// σ keys: sigma_deg, sigma_arcmin, sigma_arcsec, sigma_rad (angle inputs), sigma_px, sigma_m, sigma_mm;
// for "uniform" a half_width_<unit> key may be given instead (σ = half width / √3). Exactly one σ key per
// source; its unit family must match every input it applies to. Errors: DataError naming `where`.
std::vector<BudgetSource> ParseBudgetSources(const io::Json& sources, const BudgetModel& model,
                                             const std::string& where);

struct BudgetOptions {
  std::uint64_t samples = 20000;  // Monte Carlo draws, [0, 1e8]; 0 = Jacobian only
  std::uint64_t seed = 1;
  // --samples, --seed (io/options.h). rk-analyze budget: a flag given overrides the budget file's
  // "monte_carlo" value, which overrides the default.
  static const io::OptionTable<BudgetOptions>& Table();
  bool Check(std::string* why) const { return Table().Check(*this, why); }
};

struct BudgetOutputResult {
  double nominal = 0.0;             // SI
  double sigma_jacobian = 0.0;      // SI
  std::vector<double> by_source;    // Jacobian σ per source (SI)
  // Monte Carlo (NaN when samples = 0 or every draw failed).
  double sigma_mc = 0.0, mean_mc = 0.0, rms_mc = 0.0, p95_abs_mc = 0.0;
};

struct BudgetResult {
  std::vector<double> input_sigma;  // combined σ per input (SI)
  std::vector<BudgetOutputResult> outputs;
  Eigen::MatrixXd jacobian;
  double jacobian_check_max_rel = 0.0;  // autodiff vs central differences
  std::int64_t samples = 0, failed = 0;
};

// Throws ProcessingError if the nominal computation fails.
BudgetResult RunBudget(const BudgetModel& model, const std::vector<BudgetSource>& sources,
                       const BudgetOptions& options);
// The run's summary (io/run_summary.h): warnings for Monte Carlo draws without a solution and a singular
// Jacobian (on stderr), each output's Jacobian 1σ as headline (file units). `details` is left empty: the
// report is the budget document.
io::RunSummary BudgetSummary(const BudgetModel& model, const BudgetResult& result);

// Report document (file units: deg, arcmin for angles, px, m) and a fixed-width table.
io::Json BudgetResultToJson(const BudgetModel& model, const std::vector<BudgetSource>& sources,
                            const BudgetOptions& options, const BudgetResult& result);
std::string FormatBudgetTable(const BudgetModel& model, const std::vector<BudgetSource>& sources,
                              const BudgetResult& result);

// Central-difference Jacobian of model.Evaluate at x (steps by unit family); false if an evaluation fails.
bool NumericalJacobian(const BudgetModel& model, const Eigen::VectorXd& x, Eigen::MatrixXd* J);

}  // namespace rk::analysis
