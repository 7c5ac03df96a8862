#include "filter/adaptive_noise.h"

#include <cmath>

namespace rk::filter {

bool ParseAdaptMode(const std::string& s, AdaptMode* mode) {
  if (s == "none") *mode = AdaptMode::kNone;
  else if (s == "r") *mode = AdaptMode::kR;
  else if (s == "q") *mode = AdaptMode::kQ;
  else if (s == "qr") *mode = AdaptMode::kQR;
  else return false;
  return true;
}

const char* AdaptModeName(AdaptMode mode) {
  switch (mode) {
    case AdaptMode::kNone: return "none";
    case AdaptMode::kR: return "r";
    case AdaptMode::kQ: return "q";
    case AdaptMode::kQR: return "qr";
  }
  return "?";
}

const io::OptionTable<AdaptiveNoiseOptions>& AdaptiveNoiseOptions::Table() {
  static const io::OptionTable<AdaptiveNoiseOptions> table =
      io::OptionTable<AdaptiveNoiseOptions>()
          .Integer("--window", &AdaptiveNoiseOptions::window, "samples", io::Bounds::Closed(2, 100000),
                   "Innovation window N in samples (windowed memory, the default)")
          .Real("--fading", &AdaptiveNoiseOptions::fading, "", io::Bounds::Open(0.0, 1.0),
                "Fading-memory factor lambda in (0, 1) instead of a window");
  return table;
}

bool AdaptiveNoiseOptions::Check(std::string* why) const {
  if (!Table().Check(*this, why)) return false;
  if (!(r_floor > 0.0 && r_floor < 1.0) || !(q_floor > 0.0 && q_floor < 1.0) || !(r_ceiling > 1.0) ||
      !(q_ceiling > 1.0)) {
    *why = "adaptive noise floors must be in (0, 1) and ceilings > 1";
    return false;
  }
  return true;
}

int AdaptiveNoiseOptions::Warmup() const {
  if (memory == AdaptMemory::kWindow) return window;
  return static_cast<int>(std::ceil(1.0 / (1.0 - fading) - 1e-9));
}

void InnovationCovariance::Reset(int m, const AdaptiveNoiseOptions& options) {
  memory_ = options.memory;
  m_ = m;
  window_ = options.window;
  fading_ = options.fading;
  warmup_ = options.Warmup();
  count_ = 0;
  next_ = 0;
  weight_ = 0.0;
  S_ = ukf::MeasMat::Zero(m, m);
  C_ = ukf::MeasMat::Zero(m, m);
  S_hph_ = ukf::MeasMat::Zero(m, m);
  HPH_ = ukf::MeasMat::Zero(m, m);
  const std::size_t slots = memory_ == AdaptMemory::kWindow ? static_cast<std::size_t>(window_) : 0;
  ring_.assign(slots, ukf::MeasVec::Zero(m));
  ring_hph_.assign(slots, ukf::MeasMat::Zero(m, m));
}

void InnovationCovariance::Add(const ukf::MeasVec& d, const ukf::MeasMat& HPH) {
  ++count_;
  if (memory_ == AdaptMemory::kFading) {
    S_ = fading_ * S_ + d * d.transpose();
    S_hph_ = fading_ * S_hph_ + HPH;
    weight_ = fading_ * weight_ + 1.0;
    C_ = S_ / weight_;
    HPH_ = S_hph_ / weight_;
    return;
  }
  ring_[static_cast<std::size_t>(next_)] = d;
  ring_hph_[static_cast<std::size_t>(next_)] = HPH;
  next_ = (next_ + 1) % window_;
  const int used = count_ < window_ ? count_ : window_;
  C_.setZero();
  HPH_.setZero();
  for (int j = 0; j < used; ++j) {
    const std::size_t ju = static_cast<std::size_t>(j);
    C_.noalias() += ring_[ju] * ring_[ju].transpose();
    HPH_ += ring_hph_[ju];
  }
  C_ /= static_cast<double>(used);
  HPH_ /= static_cast<double>(used);
}

}  // namespace rk::filter
