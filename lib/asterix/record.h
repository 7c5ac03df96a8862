// One ASTERIX record: its items located with the category's UAP (uap.h), then the items rangekit uses decoded
// into plain values. No allocation, no exception: a malformed record gives its reason (a static text) and the
// offset inside the record where it went wrong, for the caller to name with the file's byte offset. The
// libFuzzer harness tests/fuzz/fuzz_asterix.cc drives DecodeBlock (block.h) over these.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "asterix/uap.h"

namespace rk::asterix {

// Where an item lies inside its record (size 0: absent).
struct ItemRef {
  std::uint16_t offset = 0;
  std::uint16_t size = 0;
};

struct RecordLayout {
  const CategorySpec* category = nullptr;
  const Uap* uap = nullptr;  // the UAP used (CAT001: plot or track, by I001/020 TYP)
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;  // octets of the record (FSPEC included)
  std::array<ItemRef, kMaxFrn> items{};  // by FRN − 1
  // The item with this number (48 for I048/048), absent when the record has none.
  ItemRef Find(std::uint16_t id) const;
  const std::uint8_t* At(ItemRef r) const { return data + r.offset; }
};

// Why a record could not be walked, and where (octets from the record's first octet).
struct RecordError {
  std::size_t offset = 0;
  const char* reason = "";
};

// Locates the items of the record at data[0, avail) (avail: what is left of its data block). False with *error
// when the FSPEC runs past the block, sets an FRN the UAP does not define, or an item runs past the block.
bool WalkRecord(const CategorySpec& category, const std::uint8_t* data, std::size_t avail, RecordLayout* out,
                RecordError* error);

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr double kMetresPerNm = 1852.0;
inline constexpr double kMetresPerFoot = 0.3048;

// A target report: CAT048 record, or a CAT001 plot or track record. NaN / −1: item absent.
struct TargetReport {
  std::uint8_t category = 0;
  bool track_record = false;  // CAT001 track layout (I001/020 TYP = 1)
  bool has_source = false;    // I0xx/010 present
  std::uint8_t sac = 0, sic = 0;
  double time_of_day_s = kNaN;            // I048/140 (full time of day, UTC, 1/128 s)
  double truncated_time_of_day_s = kNaN;  // I001/141 (time of day modulo 512 s)
  double rho_m = kNaN;                    // I048/040 (1/256 NM), I001/040 (1/128 NM)
  double theta_deg = kNaN;                // 360/2^16 deg
  double flight_level = kNaN;             // I048/090, I001/090 (1/4 FL), only when validated and not garbled
  bool flight_level_invalid = false;      // present with V or G set
  double height_m = kNaN;                 // I048/110 (25 ft)
  int mode3a = -1;                        // I048/070, I001/070: 12-bit code, only when validated and not garbled
  bool mode3a_invalid = false;
  std::int32_t address = -1;       // I048/220 (24-bit ICAO address)
  std::int32_t track_number = -1;  // I048/161 (12 bits), I001/161 (16 bits)
  std::uint8_t detection_type = 0;  // I048/020 TYP, or I001/020 (SSR/PSR bits)
  bool simulated = false;           // I0xx/020 SIM
  bool test_target = false;         // I0xx/020 TST (first extension)
};

// A CAT034 service message. NaN: item absent.
struct ServiceMessage {
  bool has_source = false;
  std::uint8_t sac = 0, sic = 0;
  std::uint8_t message_type = 0;      // I034/000: 1 north marker, 2 sector crossing, 3 geographical filtering, 4 jamming strobe, ...
  double time_of_day_s = kNaN;        // I034/030
  double sector_deg = kNaN;           // I034/020 (360/2^8)
  double rotation_period_s = kNaN;    // I034/041 (1/128 s)
};

// Decodes the items of a walked CAT048 or CAT001 record (layout.category) / CAT034 record.
TargetReport DecodeTargetReport(const RecordLayout& layout);
ServiceMessage DecodeServiceMessage(const RecordLayout& layout);

// "7000": the Mode 3/A code as its four octal digits.
std::array<char, 5> Mode3aText(int code);

}  // namespace rk::asterix
