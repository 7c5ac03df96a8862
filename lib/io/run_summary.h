// What one run of a tool found, in one shape for every tool (issue 28 item 4): rows by status, typed
// warnings, how the run ended and its headline figures. Each library's Run*/result builds it; only
// cli::WriteReport serialises it (docs/conventions.md "Run reports"), and the report page and the nightly
// index read its warnings and headline, never guessed from key names. Ceres' Summary/BriefReport is the model.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "io/json_util.h"
#include "io/row_status.h"

namespace rk::io {

// A warning with a stable snake_case `code` (for scripts: rows_skipped, not_converged, ...) and `message`, one
// sentence with its numbers, exactly as the tool prints it on stderr.
struct Warning {
  std::string code;
  std::string message;
  // false: a condition the report flags for the page without the tool having said it on stderr (outliers
  // rejected, covariance repairs), so that adding it to the report did not change what the tool prints.
  bool on_stderr = true;
};

// A figure a person looks at first (tracked frames, range coverage, a bias with its 1σ). `unit` is a unit
// ("m", "deg") or "fraction" (shown in %); `note` a few words of context ("412 of 500 frames"). A value that
// is not defined is NaN (written as null).
struct Figure {
  std::string name;
  double value = 0.0;
  std::string unit;
  std::string note;
};

struct RunSummary {
  // Rows of the tool's product by SPEC.md §2 status, indexed by RowStatus; absent for a tool whose product is
  // not a table of rows with a status (a calibration, an error budget).
  std::optional<std::array<std::size_t, 5>> rows_by_status;
  std::vector<Warning> warnings;
  // How the run ended: "completed" (no iterative solver), or the solver's outcome ("converged",
  // "not converged", "time limit", ...).
  std::string termination = "completed";
  std::vector<Figure> headline;  // in the order a person reads them
  // The tool-specific report keys (counts, options of the result, the "summary" object rk-run copies),
  // merged into the report as they are.
  Json details = Json::object();

  void Warn(std::string code, std::string message);
  // A warning for the report only (Warning::on_stderr false).
  void Flag(std::string code, std::string message);
  void AddFigure(std::string name, double value, std::string unit, std::string note = "");
  // Counts `n` rows of status `s` (makes rows_by_status present).
  void CountRows(RowStatus s, std::size_t n = 1);
  std::size_t Rows(RowStatus s) const;
  std::size_t TotalRows() const;
  // One line for a person: "500 rows: 480 ok, 20 lost; converged; tracked frames 96.0 %; 1 warning".
  std::string BriefReport() const;
};

}  // namespace rk::io
