// Shared by the filter tests (test_ukf.cc, test_adaptive_noise.cc): identities that hold to rounding.
#pragma once

namespace rk::filter {

inline constexpr double kExactTolerance = 1e-12;  // identities that hold to rounding on O(1) numbers

}  // namespace rk::filter
