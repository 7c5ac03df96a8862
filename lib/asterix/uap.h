// The layouts of the ASTERIX categories rangekit reads (EUROCONTROL specifications; the machine-readable
// definitions of github.com/zoranbosnjak/asterix-specs were the reference): CAT048 edition 1.32 (monoradar
// target reports), CAT034 edition 1.29 (monoradar service messages), CAT001 edition 1.4 (older monoradar plots,
// with its two UAPs, plot and track, chosen by I001/020 TYP). One table per category says, for every field
// reference number (FRN) of the FSPEC, which item it is and how its length is found; record.cc walks a record
// with it. Every item the tables know is skipped correctly by its length, decoded or not.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>

namespace rk::asterix {

// How an item's length is found (the structure types of the EUROCONTROL specifications).
enum class ItemKind : std::uint8_t {
  kSpare,       // "-": an FRN no item uses; a record whose FSPEC sets it is malformed
  kFixed,       // `size` octets
  kExtended,    // a first part of `size` octets, then parts of `ext_size` octets while the last octet's FX (bit 1) is set
  kRepetitive,  // a REP octet, then REP × `size` octets
  kCompound,    // a primary subfield (octets of 7 presence bits + FX), then each present subfield (`subfields`)
  kExplicit,    // a LEN octet counting itself, then LEN − 1 octets (SP, RE)
  kRfs,         // random field sequencing: N, then N × (an FRN octet + that item of the same UAP)
};

// A subfield of a compound item: kFixed (size octets), kRepetitive (REP × size) or kSpare (must be absent).
struct SubfieldSpec {
  ItemKind kind = ItemKind::kSpare;
  std::uint8_t size = 0;
};

struct ItemSpec {
  std::uint16_t id = 0;  // the item number (48 for I048/048 ...); kSpecialPurpose, kReservedExpansion, kRandomFields
  ItemKind kind = ItemKind::kSpare;
  std::uint8_t size = 0;
  std::uint8_t ext_size = 0;
  std::span<const SubfieldSpec> subfields = {};
};

inline constexpr std::uint16_t kSpecialPurpose = 1001;     // SP
inline constexpr std::uint16_t kReservedExpansion = 1002;  // RE
inline constexpr std::uint16_t kRandomFields = 1003;       // RFS

// Item numbers below this are indexed by Uap::frn_by_id (every numbered item of the categories here).
inline constexpr std::size_t kMaxItemId = 261;

// A user application profile: items[FRN − 1], and the FRN of each item number (0: not in this UAP), so that a
// decoder finds an item without searching.
struct Uap {
  std::span<const ItemSpec> items;
  std::array<std::uint8_t, kMaxItemId> frn_by_id{};
};

constexpr Uap MakeUap(std::span<const ItemSpec> items) {
  Uap u{items, {}};
  for (std::size_t i = 0; i < items.size(); ++i) {
    if (items[i].kind != ItemKind::kSpare && items[i].id < kMaxItemId) u.frn_by_id[items[i].id] = static_cast<std::uint8_t>(i + 1);
  }
  return u;
}

// Longest UAP of the categories here (28 FRNs: 4 FSPEC octets).
inline constexpr std::size_t kMaxFrn = 28;

// The categories decoded. CAT001 has two UAPs: items[0] for plots, items[1] for tracks (I001/020 TYP).
struct CategorySpec {
  std::uint8_t category = 0;
  const char* name = "";  // "CAT048"
  Uap uap;
  Uap track_uap;  // CAT001 only; empty otherwise
};

// nullptr for a category rangekit does not decode.
const CategorySpec* FindCategory(std::uint8_t category);

}  // namespace rk::asterix
