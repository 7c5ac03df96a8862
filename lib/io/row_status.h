// Per-row `status` of tool outputs, SPEC.md §2: one vocabulary for every tool.
//   ok          measured
//   predicted   no measurement, value filled by prediction
//   lost        no measurement, values empty
//   reacquired  measured again after a loss (first row back)
//   invalid     computed but failed a check, values empty
#pragma once

#include <string_view>

namespace rk {

enum class RowStatus { kOk, kReacquired, kPredicted, kLost, kInvalid };

const char* RowStatusName(RowStatus status);
// Whether a row of this status carries values (ok, reacquired, predicted); lost and invalid rows have them empty.
// A row whose status has none is never drawn or placed (rk-export).
bool RowStatusHasValues(RowStatus status);
// Parses a status name; false if `text` is not one of the five.
bool ParseRowStatus(std::string_view text, RowStatus* status);

}  // namespace rk
