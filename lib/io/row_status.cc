#include "io/row_status.h"

namespace rk {

const char* RowStatusName(RowStatus status) {
  switch (status) {
    case RowStatus::kOk:
      return "ok";
    case RowStatus::kReacquired:
      return "reacquired";
    case RowStatus::kPredicted:
      return "predicted";
    case RowStatus::kLost:
      return "lost";
    case RowStatus::kInvalid:
      return "invalid";
  }
  return "invalid";
}

bool RowStatusHasValues(RowStatus status) {
  return status == RowStatus::kOk || status == RowStatus::kReacquired || status == RowStatus::kPredicted;
}

bool ParseRowStatus(std::string_view text, RowStatus* status) {
  for (RowStatus s : {RowStatus::kOk, RowStatus::kReacquired, RowStatus::kPredicted, RowStatus::kLost,
                      RowStatus::kInvalid}) {
    if (text == RowStatusName(s)) {
      *status = s;
      return true;
    }
  }
  return false;
}

}  // namespace rk
