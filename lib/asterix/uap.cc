// The UAP tables of uap.h, item by item from the EUROCONTROL specifications (CAT048 ed. 1.32, CAT034 ed. 1.29,
// CAT001 ed. 1.4). Sizes in octets; the comment names the item.
#include "asterix/uap.h"

#include <array>

namespace rk::asterix {
namespace {

constexpr ItemSpec Fixed(std::uint16_t id, std::uint8_t size) { return {id, ItemKind::kFixed, size, 0, {}}; }
constexpr ItemSpec Extended(std::uint16_t id) { return {id, ItemKind::kExtended, 1, 1, {}}; }
constexpr ItemSpec Repetitive(std::uint16_t id, std::uint8_t size) { return {id, ItemKind::kRepetitive, size, 0, {}}; }
constexpr ItemSpec Compound(std::uint16_t id, std::span<const SubfieldSpec> subfields) {
  return {id, ItemKind::kCompound, 0, 0, subfields};
}
constexpr ItemSpec Explicit(std::uint16_t id) { return {id, ItemKind::kExplicit, 0, 0, {}}; }
constexpr ItemSpec Rfs() { return {kRandomFields, ItemKind::kRfs, 0, 0, {}}; }
constexpr ItemSpec Spare() { return {}; }
constexpr SubfieldSpec F(std::uint8_t size) { return {ItemKind::kFixed, size}; }
constexpr SubfieldSpec R(std::uint8_t size) { return {ItemKind::kRepetitive, size}; }
constexpr SubfieldSpec S() { return {}; }

// I048/130 Radar Plot Characteristics: SRL, SRR, SAM, PRL, PAM, RPD, APD, one octet each.
constexpr std::array<SubfieldSpec, 7> k048_130 = {F(1), F(1), F(1), F(1), F(1), F(1), F(1)};
// I048/120 Radial Doppler Speed: CAL (2), RDS (REP × 6).
constexpr std::array<SubfieldSpec, 2> k048_120 = {F(2), R(6)};

constexpr std::array<ItemSpec, 28> kCat048 = {
    Fixed(10, 2),               // 1  Data Source Identifier
    Fixed(140, 3),              // 2  Time of Day
    Extended(20),               // 3  Target Report Descriptor
    Fixed(40, 4),               // 4  Measured Position in Polar Co-ordinates
    Fixed(70, 2),               // 5  Mode-3/A Code
    Fixed(90, 2),               // 6  Flight Level
    Compound(130, k048_130),    // 7  Radar Plot Characteristics
    Fixed(220, 3),              // 8  Aircraft Address
    Fixed(240, 6),              // 9  Aircraft Identification
    Repetitive(250, 8),         // 10 BDS Register Data
    Fixed(161, 2),              // 11 Track Number
    Fixed(42, 4),               // 12 Calculated Position in Cartesian Co-ordinates
    Fixed(200, 4),              // 13 Calculated Track Velocity in Polar Co-ordinates
    Extended(170),              // 14 Track Status
    Fixed(210, 4),              // 15 Track Quality
    Extended(30),               // 16 Warning/Error Conditions (repetitive with FX)
    Fixed(80, 2),               // 17 Mode-3/A Code Confidence
    Fixed(100, 4),              // 18 Mode-C Code and Confidence
    Fixed(110, 2),              // 19 Height Measured by a 3D Radar
    Compound(120, k048_120),    // 20 Radial Doppler Speed
    Fixed(230, 2),              // 21 Communications/ACAS Capability and Flight Status
    Fixed(260, 7),              // 22 ACAS Resolution Advisory Report
    Fixed(55, 1),               // 23 Mode-1 Code
    Fixed(50, 2),               // 24 Mode-2 Code
    Fixed(65, 1),               // 25 Mode-1 Code Confidence
    Fixed(60, 2),               // 26 Mode-2 Code Confidence
    Explicit(kSpecialPurpose),  // 27 SP
    Explicit(kReservedExpansion),  // 28 RE
};

// I034/050 System Configuration and Status: COM, -, -, PSR, SSR, MDS (2 octets).
constexpr std::array<SubfieldSpec, 6> k034_050 = {F(1), S(), S(), F(1), F(1), F(2)};
// I034/060 System Processing Mode: COM, -, -, PSR, SSR, MDS.
constexpr std::array<SubfieldSpec, 6> k034_060 = {F(1), S(), S(), F(1), F(1), F(1)};

constexpr std::array<ItemSpec, 14> kCat034 = {
    Fixed(10, 2),                  // 1  Data Source Identifier
    Fixed(0, 1),                   // 2  Message Type
    Fixed(30, 3),                  // 3  Time of Day
    Fixed(20, 1),                  // 4  Sector Number
    Fixed(41, 2),                  // 5  Antenna Rotation Period
    Compound(50, k034_050),        // 6  System Configuration and Status
    Compound(60, k034_060),        // 7  System Processing Mode
    Repetitive(70, 2),             // 8  Message Count Values
    Fixed(100, 8),                 // 9  Generic Polar Window
    Fixed(110, 1),                 // 10 Data Filter
    Fixed(120, 8),                 // 11 3D-Position of Data Source
    Fixed(90, 2),                  // 12 Collimation Error
    Explicit(kReservedExpansion),  // 13 RE
    Explicit(kSpecialPurpose),     // 14 SP
};

constexpr std::array<ItemSpec, 21> kCat001Plot = {
    Fixed(10, 2),               // 1  Data Source Identifier
    Extended(20),               // 2  Target Report Descriptor
    Fixed(40, 4),               // 3  Measured Position in Polar Co-ordinates
    Fixed(70, 2),               // 4  Mode-3/A Code
    Fixed(90, 2),               // 5  Mode-C Code in Binary Representation
    Extended(130),              // 6  Radar Plot Characteristics (repetitive with FX)
    Fixed(141, 2),              // 7  Truncated Time of Day
    Fixed(50, 2),               // 8  Mode-2 Code
    Fixed(120, 1),              // 9  Measured Radial Doppler Speed
    Fixed(131, 1),              // 10 Received Power
    Fixed(80, 2),               // 11 Mode-3/A Code Confidence
    Fixed(100, 4),              // 12 Mode-C Code and Confidence
    Fixed(60, 2),               // 13 Mode-2 Code Confidence
    Extended(30),               // 14 Warning/Error Conditions
    Fixed(150, 1),              // 15 Presence of X-Pulse
    Spare(),                    // 16
    Spare(),                    // 17
    Spare(),                    // 18
    Spare(),                    // 19
    Explicit(kSpecialPurpose),  // 20 SP
    Rfs(),                      // 21 Random Field Sequencing
};

constexpr std::array<ItemSpec, 22> kCat001Track = {
    Fixed(10, 2),               // 1  Data Source Identifier
    Extended(20),               // 2  Target Report Descriptor
    Fixed(161, 2),              // 3  Track/Plot Number
    Fixed(40, 4),               // 4  Measured Position in Polar Co-ordinates
    Fixed(42, 4),               // 5  Calculated Position in Cartesian Co-ordinates
    Fixed(200, 4),              // 6  Calculated Track Velocity in Polar Co-ordinates
    Fixed(70, 2),               // 7  Mode-3/A Code
    Fixed(90, 2),               // 8  Mode-C Code in Binary Representation
    Fixed(141, 2),              // 9  Truncated Time of Day
    Extended(130),              // 10 Radar Plot Characteristics
    Fixed(131, 1),              // 11 Received Power
    Fixed(120, 1),              // 12 Measured Radial Doppler Speed
    Extended(170),              // 13 Track Status
    Extended(210),              // 14 Track Quality (repetitive with FX)
    Fixed(50, 2),               // 15 Mode-2 Code
    Fixed(80, 2),               // 16 Mode-3/A Code Confidence
    Fixed(100, 4),              // 17 Mode-C Code and Confidence
    Fixed(60, 2),               // 18 Mode-2 Code Confidence
    Extended(30),               // 19 Warning/Error Conditions
    Explicit(kSpecialPurpose),  // 20 SP
    Rfs(),                      // 21 Random Field Sequencing
    Fixed(150, 1),              // 22 Presence of X-Pulse
};

constexpr CategorySpec kCategories[] = {
    {48, "CAT048", MakeUap(kCat048), {}},
    {34, "CAT034", MakeUap(kCat034), {}},
    {1, "CAT001", MakeUap(kCat001Plot), MakeUap(kCat001Track)},
};

static_assert(kCat048.size() <= kMaxFrn && kCat034.size() <= kMaxFrn && kCat001Plot.size() <= kMaxFrn &&
              kCat001Track.size() <= kMaxFrn);

}  // namespace

const CategorySpec* FindCategory(std::uint8_t category) {
  for (const CategorySpec& c : kCategories) {
    if (c.category == category) return &c;
  }
  return nullptr;
}

}  // namespace rk::asterix
