// A test-side ASTERIX and capture writer, independent of the decoder: records from (FRN, octets) lists, data
// blocks, and pcap / pcapng files of Ethernet (optionally VLAN-tagged) IPv4 UDP datagrams, fragmented on request.
#pragma once

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

namespace rk::asterix::test {

using Bytes = std::vector<std::uint8_t>;

inline Bytes Be(std::uint32_t v, int n) {
  Bytes b;
  for (int i = n - 1; i >= 0; --i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  return b;
}
inline Bytes Cat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& p : parts) out.insert(out.end(), p.begin(), p.end());
  return out;
}

// A record: FSPEC from the FRNs present, then each item's octets in FRN order.
inline Bytes Record(std::vector<std::pair<int, Bytes>> items) {
  std::sort(items.begin(), items.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  const int last = items.empty() ? 1 : items.back().first;
  Bytes fspec(static_cast<std::size_t>((last + 6) / 7), 0);
  for (const auto& [frn, _] : items) fspec[static_cast<std::size_t>((frn - 1) / 7)] |= static_cast<std::uint8_t>(1u << (7 - (frn - 1) % 7));
  for (std::size_t i = 0; i + 1 < fspec.size(); ++i) fspec[i] |= 1;  // FX
  Bytes out = fspec;
  for (const auto& [_, b] : items) out.insert(out.end(), b.begin(), b.end());
  return out;
}

inline Bytes Block(std::uint8_t cat, const std::vector<Bytes>& records) {
  Bytes body;
  for (const Bytes& r : records) body.insert(body.end(), r.begin(), r.end());
  Bytes out = {cat};
  const Bytes len = Be(static_cast<std::uint32_t>(body.size() + 3), 2);
  out.insert(out.end(), len.begin(), len.end());
  out.insert(out.end(), body.begin(), body.end());
  return out;
}

// CAT048 target report items.
struct Cat048 {
  int sac = 25, sic = 10;
  double tod_s = 3600.0;
  std::uint32_t rho = 0, theta = 0;  // raw: 1/256 NM, 360/2^16 deg
  int fl_quarters = -100000;         // raw 14-bit value (×1/4 FL); −100000: absent
  bool fl_invalid = false;
  int height_25ft = -100000;         // raw 14-bit; absent
  int mode3a = -1;                   // 12-bit code
  int address = -1, track = -1;
  bool extras = true;  // also I048/020 ext, 130, 250, 170, 120, 030, SP: items to skip by their length
};

inline Bytes Cat048Record(const Cat048& c) {
  std::vector<std::pair<int, Bytes>> it;
  it.push_back({1, {static_cast<std::uint8_t>(c.sac), static_cast<std::uint8_t>(c.sic)}});
  it.push_back({2, Be(static_cast<std::uint32_t>(c.tod_s * 128 + 0.5), 3)});
  it.push_back({3, c.extras ? Bytes{0xA1, 0x02} : Bytes{0xA0}});  // TYP 5, FX; TST 0, FX 0
  it.push_back({4, Cat({Be(c.rho, 2), Be(c.theta, 2)})});
  if (c.mode3a >= 0) it.push_back({5, Be(static_cast<std::uint32_t>(c.mode3a), 2)});
  if (c.fl_quarters != -100000) {
    it.push_back({6, Be((c.fl_invalid ? 0x8000u : 0u) | (static_cast<std::uint32_t>(c.fl_quarters) & 0x3FFF), 2)});
  }
  if (c.address >= 0) it.push_back({8, Be(static_cast<std::uint32_t>(c.address), 3)});
  if (c.track >= 0) it.push_back({11, Be(static_cast<std::uint32_t>(c.track), 2)});
  if (c.height_25ft != -100000) it.push_back({19, Be(static_cast<std::uint32_t>(c.height_25ft) & 0x3FFF, 2)});
  if (c.extras) {
    it.push_back({7, {0b1010'0110, 0x11, 0x22, 0x33, 0x44}});  // 130: SRL, SAM, PAM, RPD
    it.push_back({9, Bytes(6, 0x41)});                          // 240
    it.push_back({10, Cat({{2}, Bytes(16, 0x5A)})});            // 250: REP 2 × 8
    it.push_back({14, {0x41, 0x00}});                           // 170: two parts
    it.push_back({16, {0x03, 0x05, 0x08}});                     // 030: FX chain of three
    it.push_back({20, {0xC0, 0x12, 0x34, 0x02, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12}});  // 120: CAL + RDS ×2
    it.push_back({27, {4, 0xEE, 0xEE, 0xEE}});                  // SP
  }
  return Record(std::move(it));
}

// A pcap (or pcapng) file of UDP datagrams over Ethernet.
struct Packet {
  double t_unix_s = 0.0;
  std::uint32_t src = 0x0A000001, dst = 0xE8010101;
  std::uint16_t sport = 20000, dport = 21000;
  Bytes payload;
  int fragments = 1;       // > 1: split into this many IPv4 fragments, sent last-first
  bool vlan = false;
  std::uint32_t snap = 0;  // > 0: capture only this many octets of the frame
  bool tcp = false;        // IP protocol 6 instead of UDP
  std::uint16_t ip_id = 1;
};

inline std::vector<Bytes> Frames(const Packet& p) {
  Bytes udp = Cat({Be(p.sport, 2), Be(p.dport, 2), Be(static_cast<std::uint32_t>(p.payload.size() + 8), 2), Be(0, 2)});
  udp.insert(udp.end(), p.payload.begin(), p.payload.end());
  std::vector<std::pair<std::size_t, std::size_t>> parts;  // [offset, size) of the IP payload
  const std::size_t unit = ((udp.size() / static_cast<std::size_t>(p.fragments)) + 7) / 8 * 8;
  for (std::size_t at = 0; at < udp.size(); at += unit) parts.push_back({at, std::min(unit, udp.size() - at)});
  std::vector<Bytes> frames;
  for (const auto& [at, n] : parts) {
    const bool more = at + n < udp.size();
    Bytes ip = Cat({{0x45, 0}, Be(static_cast<std::uint32_t>(20 + n), 2), Be(p.ip_id, 2),
                    Be((more ? 0x2000u : 0u) | static_cast<std::uint32_t>(at / 8), 2), {64, static_cast<std::uint8_t>(p.tcp ? 6 : 17)},
                    Be(0, 2), Be(p.src, 4), Be(p.dst, 4)});
    ip.insert(ip.end(), udp.begin() + static_cast<std::ptrdiff_t>(at), udp.begin() + static_cast<std::ptrdiff_t>(at + n));
    Bytes eth = Cat({Bytes(6, 0x01), Bytes(6, 0x02)});
    if (p.vlan) eth = Cat({eth, {0x81, 0x00, 0x00, 0x05}});
    eth = Cat({eth, {0x08, 0x00}, ip});
    frames.push_back(eth);
  }
  std::reverse(frames.begin(), frames.end());  // fragments arrive last first: reassembly must not need order
  return frames;
}

inline void Le(Bytes* b, std::uint32_t v, int n) {
  for (int i = 0; i < n; ++i) b->push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}

inline void WritePcap(const std::string& path, const std::vector<Packet>& packets) {
  Bytes f;
  Le(&f, 0xa1b2c3d4, 4);  // microseconds
  Le(&f, 2, 2);
  Le(&f, 4, 2);
  Le(&f, 0, 4);
  Le(&f, 0, 4);
  Le(&f, 65535, 4);
  Le(&f, 1, 4);  // Ethernet
  for (const Packet& p : packets) {
    for (const Bytes& frame : Frames(p)) {
      const std::uint32_t cap = p.snap > 0 ? std::min<std::uint32_t>(p.snap, static_cast<std::uint32_t>(frame.size()))
                                           : static_cast<std::uint32_t>(frame.size());
      const auto sec = static_cast<std::uint32_t>(p.t_unix_s);
      Le(&f, sec, 4);
      Le(&f, static_cast<std::uint32_t>((p.t_unix_s - sec) * 1e6 + 0.5), 4);
      Le(&f, cap, 4);
      Le(&f, static_cast<std::uint32_t>(frame.size()), 4);
      f.insert(f.end(), frame.begin(), frame.begin() + cap);
    }
  }
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(f.data()), static_cast<std::streamsize>(f.size()));
}

inline void WritePcapng(const std::string& path, const std::vector<Packet>& packets) {
  Bytes f;
  // Section header block.
  Le(&f, 0x0A0D0D0A, 4);
  Le(&f, 28, 4);
  Le(&f, 0x1A2B3C4D, 4);
  Le(&f, 1, 2);
  Le(&f, 0, 2);
  Le(&f, 0xFFFFFFFF, 4);
  Le(&f, 0xFFFFFFFF, 4);
  Le(&f, 28, 4);
  // Interface description block: Ethernet, microsecond resolution (the default).
  Le(&f, 1, 4);
  Le(&f, 20, 4);
  Le(&f, 1, 2);
  Le(&f, 0, 2);
  Le(&f, 65535, 4);
  Le(&f, 20, 4);
  for (const Packet& p : packets) {
    for (const Bytes& frame : Frames(p)) {
      const auto n = static_cast<std::uint32_t>(frame.size());
      const std::uint32_t padded = (n + 3) / 4 * 4;
      const std::uint64_t us = static_cast<std::uint64_t>(p.t_unix_s * 1e6 + 0.5);
      Le(&f, 6, 4);
      Le(&f, 32 + padded, 4);
      Le(&f, 0, 4);
      Le(&f, static_cast<std::uint32_t>(us >> 32), 4);
      Le(&f, static_cast<std::uint32_t>(us), 4);
      Le(&f, n, 4);
      Le(&f, n, 4);
      f.insert(f.end(), frame.begin(), frame.end());
      f.insert(f.end(), padded - n, 0);
      Le(&f, 32 + padded, 4);
    }
  }
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(f.data()), static_cast<std::streamsize>(f.size()));
}

}  // namespace rk::asterix::test
