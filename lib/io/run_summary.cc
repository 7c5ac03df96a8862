#include "io/run_summary.h"

#include <cmath>
#include <cstdio>

namespace rk::io {

void RunSummary::Warn(std::string code, std::string message) {
  warnings.push_back({std::move(code), std::move(message)});
}

void RunSummary::Flag(std::string code, std::string message) {
  warnings.push_back({std::move(code), std::move(message), false});
}

void RunSummary::AddFigure(std::string name, double value, std::string unit, std::string note) {
  headline.push_back({std::move(name), value, std::move(unit), std::move(note)});
}

void RunSummary::CountRows(RowStatus s, std::size_t n) {
  if (!rows_by_status) rows_by_status.emplace();
  (*rows_by_status)[static_cast<std::size_t>(s)] += n;
}

std::size_t RunSummary::Rows(RowStatus s) const {
  return rows_by_status ? (*rows_by_status)[static_cast<std::size_t>(s)] : 0;
}

std::size_t RunSummary::TotalRows() const {
  std::size_t n = 0;
  if (rows_by_status)
    for (std::size_t k : *rows_by_status) n += k;
  return n;
}

namespace {

std::string FigureText(const Figure& f) {
  if (!std::isfinite(f.value)) return f.name + " -";
  char buf[64];
  if (f.unit == "fraction") {
    std::snprintf(buf, sizeof buf, "%.1f %%", 100.0 * f.value);
  } else {
    std::snprintf(buf, sizeof buf, "%.6g%s%s", f.value, f.unit.empty() ? "" : " ", f.unit.c_str());
  }
  return f.name + " " + buf;
}

}  // namespace

std::string RunSummary::BriefReport() const {
  std::string out;
  if (rows_by_status) {
    out = std::to_string(TotalRows()) + " rows";
    const char* sep = ": ";
    for (RowStatus s : {RowStatus::kOk, RowStatus::kReacquired, RowStatus::kPredicted, RowStatus::kLost,
                        RowStatus::kInvalid}) {
      if (Rows(s) == 0) continue;
      out += sep + std::to_string(Rows(s)) + " " + RowStatusName(s);
      sep = ", ";
    }
    out += "; ";
  }
  out += termination;
  for (const Figure& f : headline) out += "; " + FigureText(f);
  if (!warnings.empty()) {
    out += "; " + std::to_string(warnings.size()) + (warnings.size() == 1 ? " warning" : " warnings");
  }
  return out;
}

}  // namespace rk::io
