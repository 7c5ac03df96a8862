// The smoothed-series writer; see smoothed_series.h.
#include "filter/smoothed_series.h"

#include "filter/singer_series.h"  // AngleColumnsIn360
#include "geo/angles.h"

namespace rk::filter {
namespace {

std::vector<std::string> Header(const Series& s, const SmoothedColumns& c) {
  std::vector<std::string> h = {"t_s"};
  h.insert(h.end(), c.copied.begin(), c.copied.end());
  h.push_back("kind");
  h.insert(h.end(), s.columns.begin(), s.columns.end());
  h.push_back("status");
  if (c.reason) h.push_back("reason");
  if (c.derivatives) {
    for (const auto& name : s.columns) {
      h.push_back(DerivedColumnName(name, 1));
      h.push_back(DerivedColumnName(name, 2));
    }
  }
  for (const auto& name : s.columns) {
    for (int order = 0; order < c.sigma_orders; ++order) h.push_back(DerivedColumnName(name, order, true));
  }
  return h;
}

}  // namespace

SmoothedSeriesWriter::SmoothedSeriesWriter(const Series& series, SmoothedColumns columns, int decimals)
    : series_(series),
      cols_(std::move(columns)),
      decimals_(decimals),
      in360_(AngleColumnsIn360(series)),
      x_(3, static_cast<Eigen::Index>(series.columns.size())),
      sd_(3, static_cast<Eigen::Index>(series.columns.size())),
      w_(Header(series, cols_)) {
  for (std::size_t c = 0; c < series.columns.size(); ++c) unit_.push_back(series.is_angle[c] ? geo::RadToDeg(1.0) : 1.0);
  x_.setConstant(kEmpty);
  sd_.setConstant(kEmpty);
}

void SmoothedSeriesWriter::Set(std::size_t c, double value, double rate, double accel) {
  const Eigen::Index k = static_cast<Eigen::Index>(c);
  x_(0, k) = value, x_(1, k) = rate, x_(2, k) = accel;
}

void SmoothedSeriesWriter::SetSigma(std::size_t c, int order, double sigma) { sd_(order, static_cast<Eigen::Index>(c)) = sigma; }

void SmoothedSeriesWriter::Write(double t_s, std::string_view kind, std::string_view status, std::string_view reason,
                                 const std::vector<std::string_view>* copied) {
  const std::size_t nc = series_.columns.size();
  w_.Add(t_s, decimals_);
  if (copied) {
    for (std::string_view cell : *copied) w_.Add(cell);
  }
  w_.Add(kind);
  for (std::size_t c = 0; c < nc; ++c) {
    double v = x_(0, static_cast<Eigen::Index>(c));
    if (series_.is_angle[c]) {
      const double deg = geo::RadToDeg(v);
      v = in360_[c] ? geo::WrapDeg360(deg) : geo::WrapDeg180(deg);
    }
    w_.Add(v, decimals_);  // a non-finite number is an empty field (io::CsvWriter)
  }
  w_.Add(status);
  if (cols_.reason) w_.Add(reason);
  if (cols_.derivatives) {
    for (std::size_t c = 0; c < nc; ++c) {
      const Eigen::Index k = static_cast<Eigen::Index>(c);
      w_.Add(unit_[c] * x_(1, k), decimals_).Add(unit_[c] * x_(2, k), decimals_);
    }
  }
  for (std::size_t c = 0; c < nc; ++c) {
    for (int order = 0; order < cols_.sigma_orders; ++order) {
      w_.Add(unit_[c] * sd_(order, static_cast<Eigen::Index>(c)), decimals_);
    }
  }
  w_.EndRow();
  x_.setConstant(kEmpty);
  sd_.setConstant(kEmpty);
}

}  // namespace rk::filter
