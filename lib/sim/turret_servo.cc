#include "sim/turret_servo.h"

#include <algorithm>
#include <cmath>
#include <random>

#include "geo/angles.h"
#include "io/error.h"

namespace rk::sim {
namespace {

constexpr int kJitterTones = 8;

}  // namespace

const io::OptionTable<TurretServoOptions>& TurretServoOptions::Table() {
  static const io::OptionTable<TurretServoOptions> table =
      io::OptionTable<TurretServoOptions>()
          .Real("--turret-lag-s", &TurretServoOptions::lag_s, "s", io::Bounds::Closed(0.0, 2.0),
                "Turret servo time constant (s); 0 = no lag")
          .Real("--jitter-arcsec", &TurretServoOptions::jitter_arcsec, "arcsec",
                io::Bounds::Closed(0.0, 0.01 * geo::kArcsecPerRad), "Turret jitter RMS per axis (arcsec); 0 = none")
          .Real("--jitter-min-hz", &TurretServoOptions::jitter_min_hz, "Hz", io::Bounds::Positive(),
                "Lowest jitter frequency (Hz)")
          .Real("--jitter-max-hz", &TurretServoOptions::jitter_max_hz, "Hz", io::Bounds::LeftOpen(0.0, 100.0),
                "Highest jitter frequency (Hz)");
  return table;
}

bool TurretServoOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (!(jitter_max_hz >= jitter_min_hz)) {
    if (why) *why = "--jitter-max-hz must be >= --jitter-min-hz";
    return false;
  }
  return true;
}

TurretServo::TurretServo(const TurretServoOptions& opt, const std::function<Eigen::Vector3d(double)>& target_enu,
                         double t_begin_s, double t_end_s, std::uint64_t seed)
    : opt_(opt), t_begin_s_(t_begin_s) {
  RK_CHECK(t_end_s > t_begin_s, "servo time span");
  const auto n = static_cast<std::size_t>(std::ceil((t_end_s - t_begin_s) / h_s_)) + 2;
  std::vector<double> u_az(n), u_el(n);
  double prev_az = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const geo::AzEl ae = geo::AzElFromEnu(target_enu(t_begin_s + static_cast<double>(i) * h_s_));
    double az = ae.az_rad;
    if (i > 0) az = prev_az + geo::AngleDiff(az, prev_az);  // unwrap
    u_az[i] = az;
    u_el[i] = ae.el_rad;
    prev_az = az;
  }
  az_.resize(n);
  el_.resize(n);
  daz_.resize(n);
  del_.resize(n);
  const double tau = opt.lag_s;
  auto integrate = [&](const std::vector<double>& u, std::vector<double>& x, std::vector<double>& dx) {
    if (tau <= 0.0) {
      for (std::size_t i = 0; i < n; ++i) {
        x[i] = u[i];
        const std::size_t a = i == 0 ? 0 : i - 1, b = std::min(n - 1, i + 1);
        dx[i] = (u[b] - u[a]) / (static_cast<double>(b - a) * h_s_);
      }
      return;
    }
    const double alpha = std::exp(-h_s_ / tau);
    x[0] = u[0] - tau * (u[1] - u[0]) / h_s_;  // steady state for the initial rate
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double s = (u[i + 1] - u[i]) / h_s_;
      x[i + 1] = u[i + 1] - s * tau + (x[i] - u[i] + s * tau) * alpha;
    }
    for (std::size_t i = 0; i < n; ++i) dx[i] = (u[i] - x[i]) / tau;
  };
  integrate(u_az, az_, daz_);
  integrate(u_el, el_, del_);

  std::seed_seq seq{seed, std::uint64_t{0x7u}};
  std::mt19937_64 rng(seq);
  std::uniform_real_distribution<double> freq(opt.jitter_min_hz, opt.jitter_max_hz);
  std::uniform_real_distribution<double> phase(0.0, geo::kTwoPi);
  for (int k = 0; k < kJitterTones; ++k) {
    f_az_.push_back(freq(rng));
    ph_az_.push_back(phase(rng));
    f_el_.push_back(freq(rng));
    ph_el_.push_back(phase(rng));
  }
  amp_rad_ = opt.jitter_rms_rad() * std::sqrt(2.0 / kJitterTones);
}

double TurretServo::Interp(const std::vector<double>& x, const std::vector<double>& dx, double t_s) const {
  const double u = (t_s - t_begin_s_) / h_s_;
  RK_CHECK(u >= -1e-9 && u <= static_cast<double>(x.size() - 1) + 1e-9, "servo time outside the simulated span");
  auto i = static_cast<std::size_t>(std::clamp(std::floor(u), 0.0, static_cast<double>(x.size() - 2)));
  const double s = u - static_cast<double>(i);
  const double s2 = s * s, s3 = s2 * s;
  const double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  return h00 * x[i] + h10 * h_s_ * dx[i] + h01 * x[i + 1] + h11 * h_s_ * dx[i + 1];
}

double TurretServo::Jitter(const std::vector<double>& f, const std::vector<double>& ph, double t_s) const {
  if (amp_rad_ == 0.0) return 0.0;
  double j = 0.0;
  for (std::size_t k = 0; k < f.size(); ++k) j += std::sin(geo::kTwoPi * f[k] * t_s + ph[k]);
  return amp_rad_ * j;
}

geo::AzEl TurretServo::ServoState(double t_s) const {
  return {geo::WrapTwoPi(Interp(az_, daz_, t_s)), Interp(el_, del_, t_s)};
}

geo::AzEl TurretServo::Boresight(double t_s) const {
  return {geo::WrapTwoPi(Interp(az_, daz_, t_s) + Jitter(f_az_, ph_az_, t_s)),
          Interp(el_, del_, t_s) + Jitter(f_el_, ph_el_, t_s)};
}

}  // namespace rk::sim
