// Angle helpers. Inside the library angles are radians; degrees exist only at
// the file boundary. Differences are wrapped to (-pi, pi] (SPEC.md §2: (-180, 180]),
// azimuths to [0, 2 pi).
#pragma once

#include <cmath>
#include <numbers>

namespace rk::geo {

inline constexpr double kPi = std::numbers::pi;
inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
inline constexpr double kArcsecPerRad = 180.0 / std::numbers::pi * 3600.0;

inline constexpr double DegToRad(double deg) { return deg * (kPi / 180.0); }
inline constexpr double RadToDeg(double rad) { return rad * (180.0 / kPi); }

// Wraps to (-pi, pi].
inline double WrapPi(double a) {
  double w = std::remainder(a, kTwoPi);  // in [-pi, pi]
  return w <= -kPi ? w + kTwoPi : w;
}
// Wraps to [0, 2 pi).
inline double WrapTwoPi(double a) {
  double w = std::fmod(a, kTwoPi);
  if (w < 0) w += kTwoPi;
  return w >= kTwoPi ? 0.0 : w;
}
// Wraps to (-180, 180].
inline double WrapDeg180(double a) {
  double w = std::remainder(a, 360.0);
  return w <= -180.0 ? w + 360.0 : w;
}
// Wraps to [0, 360).
inline double WrapDeg360(double a) {
  double w = std::fmod(a, 360.0);
  if (w < 0) w += 360.0;
  return w >= 360.0 ? 0.0 : w;
}
// a - b wrapped to (-pi, pi].
inline double AngleDiff(double a, double b) { return WrapPi(a - b); }

}  // namespace rk::geo
