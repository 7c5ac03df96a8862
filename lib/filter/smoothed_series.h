// The smoothed series (SPEC.md §2.1 `t_s,kind,<value columns>`), as rk-smooth aukf, singer and resample write
// it — one writer, so that the three agree on the columns' order, their names (DerivedColumnName), the units
// (angles in degrees, each wrapped to the range its input column uses, AngleColumnsIn360) and empty fields:
//   t_s, [the copied columns of resample's --at], kind, the value columns, status, [reason],
//   [per column: its rate and acceleration], [per column: its 1σ, and with sigma_orders 3 its rate's and
//   acceleration's 1σ].
#pragma once

#include <Eigen/Core>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "filter/series.h"
#include "io/csv.h"

namespace rk::filter {

struct SmoothedColumns {
  std::vector<std::string> copied;  // columns of another table copied after t_s (rk-smooth resample --at)
  bool reason = false;              // a `reason` column after status (resample)
  bool derivatives = false;         // rate and acceleration columns
  int sigma_orders = 0;             // 1σ columns per value column: 0 none, 1 the value's, 3 value, rate, accel
};

class SmoothedSeriesWriter {
 public:
  SmoothedSeriesWriter(const Series& series, SmoothedColumns columns, int decimals);

  // One row: what the row has of column c (SI units, angles in radians; a non-finite number is an empty
  // field), then Write. Set fills the value and, with derivatives, rate and acceleration; SetSigma order 0, 1, 2.
  // Every field starts empty again after Write.
  void Set(std::size_t c, double value, double rate = kEmpty, double accel = kEmpty);
  void SetSigma(std::size_t c, int order, double sigma);
  // `copied`: one cell per SmoothedColumns::copied (nullptr without them).
  void Write(double t_s, std::string_view kind, std::string_view status, std::string_view reason = {},
             const std::vector<std::string_view>* copied = nullptr);

  std::string TakeText() { return w_.TakeText(); }  // the text so far (streamed output)
  io::CsvWriter& csv() { return w_; }

  static constexpr double kEmpty = std::numeric_limits<double>::quiet_NaN();

 private:
  const Series& series_;
  SmoothedColumns cols_;
  int decimals_;
  std::vector<bool> in360_;
  std::vector<double> unit_;                  // deg per rad for an angle column, else 1
  Eigen::Matrix<double, 3, Eigen::Dynamic> x_;   // value, rate, accel per column
  Eigen::Matrix<double, 3, Eigen::Dynamic> sd_;  // their 1σ
  io::CsvWriter w_;
};

}  // namespace rk::filter
