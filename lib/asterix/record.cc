#include "asterix/record.h"

#include "asterix/big_endian.h"

namespace rk::asterix {
namespace {

// A two's-complement field of `bits` bits in the low bits of v.
std::int32_t Signed(std::uint32_t v, int bits) {
  const std::uint32_t sign = 1u << (bits - 1);
  v &= (sign << 1) - 1;
  return static_cast<std::int32_t>(v ^ sign) - static_cast<std::int32_t>(sign);
}

// Octets of a sequence of parts chained by FX (bit 1 of a part's last octet): first part `first`, then
// `next`.
std::size_t FxChainLength(const std::uint8_t* p, std::size_t avail, std::size_t first, std::size_t next,
                          const char** why) {
  std::size_t n = first;
  for (;;) {
    if (n > avail) {
      *why = "item runs past the end of its data block (FX set in its last octet)";
      return 0;
    }
    if (!(p[n - 1] & 1)) return n;
    n += next;
  }
}

// Octets of one item at p (avail octets left in the block); 0 with *why when it does not fit. RFS is handled
// by WalkRecord (it needs the UAP).
std::size_t ItemLength(const ItemSpec& s, const std::uint8_t* p, std::size_t avail, const char** why) {
  switch (s.kind) {
    case ItemKind::kFixed:
      if (s.size > avail) break;
      return s.size;
    case ItemKind::kExtended:
      return FxChainLength(p, avail, s.size, s.ext_size, why);
    case ItemKind::kRepetitive: {
      if (avail < 1) break;
      const std::size_t n = 1 + std::size_t{p[0]} * s.size;
      if (n > avail) break;
      return n;
    }
    case ItemKind::kExplicit: {
      if (avail < 1) break;
      if (p[0] == 0) {
        *why = "explicit-length item (SP/RE) of length 0";
        return 0;
      }
      if (p[0] > avail) break;
      return p[0];
    }
    case ItemKind::kCompound: {
      const std::size_t primary = FxChainLength(p, avail, 1, 1, why);
      if (primary == 0) return 0;
      std::size_t n = primary;
      for (std::size_t octet = 0; octet < primary; ++octet) {
        for (int bit = 7; bit >= 1; --bit) {
          if (!(p[octet] & (1u << bit))) continue;
          const std::size_t index = octet * 7 + static_cast<std::size_t>(7 - bit);
          if (index >= s.subfields.size() || s.subfields[index].kind == ItemKind::kSpare) {
            *why = "compound item sets a subfield its specification does not define";
            return 0;
          }
          const SubfieldSpec& sub = s.subfields[index];
          if (sub.kind == ItemKind::kFixed) {
            n += sub.size;
          } else {  // kRepetitive: its REP octet must be inside the block
            if (n >= avail) {
              *why = "item runs past the end of its data block";
              return 0;
            }
            n += 1 + std::size_t{p[n]} * sub.size;
          }
          if (n > avail) {
            *why = "item runs past the end of its data block";
            return 0;
          }
        }
      }
      if (n > avail) break;
      return n;
    }
    case ItemKind::kSpare:
    case ItemKind::kRfs:
      *why = "FSPEC sets a field reference number its UAP does not use";
      return 0;
  }
  *why = "item runs past the end of its data block";
  return 0;
}

// Sets the item of `frn` (1-based) at [offset, offset + length) of the record.
bool Place(RecordLayout* out, std::size_t frn, std::size_t offset, std::size_t length, const char** why) {
  ItemRef& r = out->items[frn - 1];
  if (r.size != 0) {
    *why = "an item appears twice (random field sequencing repeats one)";
    return false;
  }
  r.offset = static_cast<std::uint16_t>(offset);
  r.size = static_cast<std::uint16_t>(length);
  return true;
}

}  // namespace

ItemRef RecordLayout::Find(std::uint16_t id) const {
  if (id < kMaxItemId) {
    const std::size_t frn = uap->frn_by_id[id];
    return frn == 0 ? ItemRef{} : items[frn - 1];
  }
  for (std::size_t i = 0; i < uap->items.size(); ++i) {
    if (uap->items[i].id == id && uap->items[i].kind != ItemKind::kSpare) return items[i];
  }
  return {};
}

bool WalkRecord(const CategorySpec& category, const std::uint8_t* data, std::size_t avail, RecordLayout* out,
                RecordError* error) {
  // Records inside a data block of at most 65535 octets: offsets fit the 16-bit ItemRef.
  if (avail > 65535) avail = 65535;
  *out = RecordLayout{};
  out->category = &category;
  out->uap = &category.uap;
  out->data = data;
  const char* why = "";
  // FSPEC: octets of 7 FRN bits + FX, no longer than the longest UAP of the category needs.
  const std::size_t max_frn = category.track_uap.items.size() > category.uap.items.size()
                                  ? category.track_uap.items.size()
                                  : category.uap.items.size();
  std::size_t fspec = 0;
  for (;;) {
    if (fspec >= avail) {
      *error = {fspec, "FSPEC runs past the end of its data block"};
      return false;
    }
    ++fspec;
    if (!(data[fspec - 1] & 1)) break;
    if (fspec * 7 >= max_frn) {
      *error = {fspec - 1, "FSPEC is longer than the category's UAP"};
      return false;
    }
  }
  std::size_t pos = fspec;
  // The FRNs set, in order: per FSPEC octet, its presence bits from the highest.
  bool uap_chosen = false;  // CAT001: from the first FRN past 2, whether or not FRN 3 is present
  for (std::size_t octet = 0; octet < fspec; ++octet) {
    for (unsigned bits = data[octet] & 0xFEu; bits != 0;) {
      const unsigned top = 31u - static_cast<unsigned>(__builtin_clz(bits));  // 7 (FRN 7·octet + 1) .. 1
      bits &= ~(1u << top);
      const std::size_t frn = octet * 7 + (8 - top);
      // CAT001: the plot and track UAPs share FRN 1 (010) and 2 (020); I001/020 TYP chooses from FRN 3 on.
      if (frn >= 3 && !uap_chosen && !category.track_uap.items.empty()) {
        uap_chosen = true;
        const ItemRef typ = out->items[1];
        if (typ.size == 0) {
          *error = {pos, "CAT001 record without I001/020: plot or track layout unknown"};
          return false;
        }
        if (data[typ.offset] & 0x80) out->uap = &category.track_uap;
      }
      if (frn > out->uap->items.size()) {
        *error = {octet, "FSPEC sets a field reference number beyond the category's UAP"};
        return false;
      }
      const ItemSpec& spec = out->uap->items[frn - 1];
      if (spec.kind == ItemKind::kSpare) {
        *error = {octet, "FSPEC sets a field reference number its UAP does not use"};
        return false;
      }
      std::size_t length = 0;
      if (spec.kind == ItemKind::kRfs) {
        // N, then N × (FRN, item).
        if (pos >= avail) {
          *error = {pos, "item runs past the end of its data block"};
          return false;
        }
        const std::size_t count = data[pos];
        std::size_t p = pos + 1;
        for (std::size_t k = 0; k < count; ++k) {
          if (p >= avail) {
            *error = {p, "random field sequencing runs past the end of its data block"};
            return false;
          }
          const std::size_t inner = data[p];
          if (inner == 0 || inner > out->uap->items.size() ||
              out->uap->items[inner - 1].kind == ItemKind::kRfs ||
              out->uap->items[inner - 1].kind == ItemKind::kSpare) {
            *error = {p, "random field sequencing names a field reference number its UAP does not use"};
            return false;
          }
          const std::size_t n = ItemLength(out->uap->items[inner - 1], data + p + 1, avail - p - 1, &why);
          if (n == 0 || !Place(out, inner, p + 1, n, &why)) {
            *error = {p + 1, why};
            return false;
          }
          p += 1 + n;
        }
        length = p - pos;
      } else {
        length = ItemLength(spec, data + pos, avail - pos, &why);
        if (length == 0) {
          *error = {pos, why};
          return false;
        }
      }
      if (!Place(out, frn, pos, length, &why)) {
        *error = {pos, why};
        return false;
      }
      pos += length;
    }
  }
  out->size = pos;
  return true;
}

TargetReport DecodeTargetReport(const RecordLayout& r) {
  TargetReport t;
  t.category = r.category->category;
  const bool cat001 = t.category == 1;
  t.track_record = cat001 && r.uap == &r.category->track_uap;
  if (const ItemRef i = r.Find(10); i.size) {
    t.has_source = true;
    t.sac = r.At(i)[0];
    t.sic = r.At(i)[1];
  }
  if (const ItemRef i = r.Find(20); i.size) {
    const std::uint8_t first = r.At(i)[0];
    if (cat001) {
      t.simulated = first & 0x40;
      t.detection_type = (first >> 4) & 3;  // SSR/PSR: 1 PSR only, 2 SSR only, 3 both
    } else {
      t.simulated = first & 0x10;
      t.detection_type = first >> 5;
    }
    if (i.size > 1) t.test_target = r.At(i)[1] & 0x80;
  }
  if (const ItemRef i = r.Find(140); i.size) t.time_of_day_s = Be24(r.At(i)) / 128.0;
  if (const ItemRef i = r.Find(141); i.size) t.truncated_time_of_day_s = Be16(r.At(i)) / 128.0;
  if (const ItemRef i = r.Find(40); i.size) {
    const std::uint8_t* p = r.At(i);
    t.rho_m = Be16(p) * (cat001 ? kMetresPerNm / 128.0 : kMetresPerNm / 256.0);
    t.theta_deg = Be16(p + 2) * (360.0 / 65536.0);
  }
  if (const ItemRef i = r.Find(70); i.size) {
    const std::uint32_t v = Be16(r.At(i));
    if (v & 0xC000) {  // V (not validated) or G (garbled)
      t.mode3a_invalid = true;
    } else {
      t.mode3a = static_cast<int>(v & 0x0FFF);
    }
  }
  if (const ItemRef i = r.Find(90); i.size) {
    const std::uint32_t v = Be16(r.At(i));
    if (v & 0xC000) {
      t.flight_level_invalid = true;
    } else {
      t.flight_level = Signed(v, 14) / 4.0;
    }
  }
  if (!cat001) {
    if (const ItemRef i = r.Find(110); i.size) t.height_m = Signed(Be16(r.At(i)), 14) * 25.0 * kMetresPerFoot;
    if (const ItemRef i = r.Find(220); i.size) t.address = static_cast<std::int32_t>(Be24(r.At(i)));
    if (const ItemRef i = r.Find(161); i.size)
      t.track_number = static_cast<std::int32_t>(Be16(r.At(i)) & 0x0FFF);
  } else if (const ItemRef i = r.Find(161); i.size) {
    t.track_number = static_cast<std::int32_t>(Be16(r.At(i)));
  }
  return t;
}

ServiceMessage DecodeServiceMessage(const RecordLayout& r) {
  ServiceMessage m;
  if (const ItemRef i = r.Find(10); i.size) {
    m.has_source = true;
    m.sac = r.At(i)[0];
    m.sic = r.At(i)[1];
  }
  if (const ItemRef i = r.Find(0); i.size) m.message_type = r.At(i)[0];
  if (const ItemRef i = r.Find(30); i.size) m.time_of_day_s = Be24(r.At(i)) / 128.0;
  if (const ItemRef i = r.Find(20); i.size) m.sector_deg = r.At(i)[0] * (360.0 / 256.0);
  if (const ItemRef i = r.Find(41); i.size) m.rotation_period_s = Be16(r.At(i)) / 128.0;
  return m;
}

std::array<char, 5> Mode3aText(int code) {
  std::array<char, 5> s{};
  for (int d = 0; d < 4; ++d)
    s[static_cast<std::size_t>(d)] = static_cast<char>('0' + ((code >> (9 - 3 * d)) & 7));
  s[4] = '\0';
  return s;
}

}  // namespace rk::asterix
