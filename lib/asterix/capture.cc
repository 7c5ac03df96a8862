#include "asterix/capture.h"

#include "asterix/big_endian.h"

#include <pcap/pcap.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <tuple>
#include <vector>

#include "io/error.h"
#include "io/file_util.h"

namespace rk::asterix {
namespace {


enum class FileKind { kPcap, kPcapModified, kPcapng, kRaw };

FileKind KindOfMagic(const std::uint8_t* m, std::size_t n) {
  switch (n >= 4 ? Be32(m) : 0) {
    case 0xa1b2c3d4: case 0xd4c3b2a1: case 0xa1b23c4d: case 0x4d3cb2a1: return FileKind::kPcap;
    case 0xa1b2cd34: case 0x34cdb2a1: return FileKind::kPcapModified;
    case 0x0a0d0d0a: return FileKind::kPcapng;
    default: return FileKind::kRaw;
  }
}

FileKind KindOf(const std::string& path) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(path.c_str(), "rb"), &std::fclose);
  if (!f) throw IoError(path, std::strerror(errno));
  std::array<std::uint8_t, 4> m{};
  const FileKind kind = KindOfMagic(m.data(), std::fread(m.data(), 1, m.size(), f.get()));
  const auto ends = [&](const char* ext) {
    const std::size_t e = std::strlen(ext);
    return path.size() >= e && path.compare(path.size() - e, e, ext) == 0;
  };
  if (kind == FileKind::kRaw && (ends(".pcap") || ends(".pcapng") || ends(".cap"))) {
    throw ByteOffsetError(path, 0, "named as a packet capture but is not pcap or pcapng (no capture magic number)");
  }
  return kind;
}

// IPv4 fragments of one datagram, gathered until they cover it.
struct Pending {
  std::vector<std::uint8_t> data = std::vector<std::uint8_t>(65536);
  std::vector<bool> have = std::vector<bool>(8192);  // per 8-octet unit
  std::size_t total = std::numeric_limits<std::size_t>::max();  // known from the last fragment
  double first_unix_s = 0.0;
  std::uint64_t first_offset = 0;  // file offset of the first fragment's IP payload (when offset 0 arrives)
  bool Complete() const {
    if (total == std::numeric_limits<std::size_t>::max()) return false;
    for (std::size_t u = 0; u < (total + 7) / 8; ++u) {
      if (!have[u]) return false;
    }
    return true;
  }
};
using FragmentKey = std::tuple<std::uint32_t, std::uint32_t, std::uint16_t>;  // src, dst, identification

class PacketReader {
 public:
  PacketReader(const std::string& path, const std::function<void(const Datagram&)>& on_datagram,
               const CaptureProblem& on_problem, CaptureStats* stats)
      : path_(path), on_datagram_(on_datagram), on_problem_(on_problem), stats_(stats) {}

  // One captured packet of link type `dlt`; `offset`: file offset of its first octet.
  void Packet(int dlt, const std::uint8_t* p, std::size_t caplen, std::size_t len, double unix_s,
              std::uint64_t offset, std::uint64_t number) {
    ++stats_->packets;
    if (caplen < len) ++stats_->truncated_packets;
    std::size_t pos = 0;
    bool ipv4 = false;
    switch (dlt) {
      case DLT_EN10MB: {
        if (caplen < 14) break;
        std::uint32_t type = Be16(p + 12);
        pos = 14;
        while ((type == 0x8100 || type == 0x88a8 || type == 0x9100) && caplen >= pos + 4) {
          type = Be16(p + pos + 2);
          pos += 4;
        }
        ipv4 = type == 0x0800;
        break;
      }
      case DLT_LINUX_SLL:
        if (caplen >= 16) ipv4 = Be16(p + 14) == 0x0800, pos = 16;
        break;
      case DLT_LINUX_SLL2:
        if (caplen >= 20) ipv4 = Be16(p) == 0x0800, pos = 20;
        break;
      case DLT_RAW:
#ifdef DLT_IPV4
      case DLT_IPV4:
#endif
        ipv4 = caplen >= 1 && (p[0] >> 4) == 4;
        break;
      case DLT_NULL:
      case DLT_LOOP:
        if (caplen >= 4) {
          std::uint32_t family;
          std::memcpy(&family, p, 4);
          ipv4 = family == 2 || family == 0x02000000u;  // AF_INET in either byte order
          pos = 4;
        }
        break;
      default:
        break;
    }
    if (!ipv4 || caplen < pos + 20) {
      ++stats_->other_packets;
      return;
    }
    const std::uint8_t* ip = p + pos;
    const std::size_t ihl = std::size_t{ip[0] & 0x0Fu} * 4;
    const std::size_t total = Be16(ip + 2);
    if ((ip[0] >> 4) != 4 || ihl < 20 || total < ihl) {
      on_problem_(offset + pos, "packet " + std::to_string(number) + ": malformed IPv4 header");
      return;
    }
    if (ip[9] != 17) {  // not UDP
      ++stats_->other_packets;
      return;
    }
    const std::size_t have = caplen - pos;  // octets of the IP datagram in the capture (Ethernet padding included)
    if (have < total) {
      on_problem_(offset + pos, "packet " + std::to_string(number) + ": cut by the capture's snap length (" +
                                    std::to_string(caplen) + " of " + std::to_string(len) + " octets captured)");
      return;
    }
    const std::uint32_t flags = Be16(ip + 6);
    const bool more = flags & 0x2000;
    const std::size_t frag_offset = std::size_t{flags & 0x1FFFu} * 8;
    const std::uint32_t src = Be32(ip + 12), dst = Be32(ip + 16);
    if (!more && frag_offset == 0) {
      Udp(ip + ihl, total - ihl, unix_s, offset + pos + ihl, false, number, src, dst);
      return;
    }
    ++stats_->fragments;
    Fragment(ip + ihl, total - ihl, more, frag_offset, unix_s, offset + pos + ihl, number, src, dst, static_cast<std::uint16_t>(Be16(ip + 4)));
  }

  // Fragments older than this capture time never complete.
  void ExpireFragments(double before_unix_s) {
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (it->second.first_unix_s < before_unix_s) {
        ++stats_->incomplete_datagrams;
        it = pending_.erase(it);
      } else {
        ++it;
      }
    }
  }
  void Finish() {
    stats_->incomplete_datagrams += pending_.size();
    pending_.clear();
  }

 private:
  void Fragment(const std::uint8_t* p, std::size_t n, bool more, std::size_t at, double unix_s, std::uint64_t offset,
                std::uint64_t number, std::uint32_t src, std::uint32_t dst, std::uint16_t id) {
    if (at + n > 65535 || (more && n % 8 != 0)) {
      on_problem_(offset, "packet " + std::to_string(number) + ": IPv4 fragment outside a datagram's 65535 octets");
      return;
    }
    Pending& d = pending_[{src, dst, id}];
    if (d.first_unix_s == 0.0) d.first_unix_s = unix_s;
    std::memcpy(d.data.data() + at, p, n);
    for (std::size_t u = at / 8; u < (at + n + 7) / 8; ++u) d.have[u] = true;
    if (at == 0) d.first_offset = offset;
    if (!more) d.total = at + n;
    if (!d.Complete()) return;
    ++stats_->reassembled;
    const Pending done = std::move(d);
    pending_.erase({src, dst, id});
    Udp(done.data.data(), done.total, unix_s, done.first_offset, true, number, src, dst);
  }

  void Udp(const std::uint8_t* u, std::size_t n, double unix_s, std::uint64_t offset, bool reassembled,
           std::uint64_t number, std::uint32_t src, std::uint32_t dst) {
    const std::size_t length = n >= 8 ? Be16(u + 4) : 0;
    if (n < 8 || length < 8 || length > n) {
      on_problem_(offset, "packet " + std::to_string(number) + ": UDP length does not fit its IP datagram");
      return;
    }
    ++stats_->udp_datagrams;
    Datagram d;
    d.data = u + 8;
    d.size = length - 8;
    d.capture_unix_s = unix_s;
    d.file_offset = offset + 8;
    d.reassembled = reassembled;
    d.packet = number;
    d.src_ip = src;
    d.dst_ip = dst;
    d.src_port = static_cast<std::uint16_t>(Be16(u));
    d.dst_port = static_cast<std::uint16_t>(Be16(u + 2));
    on_datagram_(d);
  }

  const std::string& path_;
  const std::function<void(const Datagram&)>& on_datagram_;
  const CaptureProblem& on_problem_;
  CaptureStats* stats_;
  std::map<FragmentKey, Pending> pending_;
};

// `file`: the open capture (nullptr: open `path`); libpcap closes it.
void ReadPcap(const std::string& path, std::FILE* file_in, FileKind kind,
              const std::function<void(const Datagram&)>& on_datagram, const CaptureProblem& on_problem,
              CaptureStats* stats) {
  std::array<char, PCAP_ERRBUF_SIZE> err{};
  pcap_t* raw = file_in ? pcap_fopen_offline_with_tstamp_precision(file_in, PCAP_TSTAMP_PRECISION_NANO, err.data())
                        : pcap_open_offline_with_tstamp_precision(path.c_str(), PCAP_TSTAMP_PRECISION_NANO, err.data());
  if (raw == nullptr) {
    if (file_in) std::fclose(file_in);
    // The magic number was right (KindOf): what libpcap refuses is the file's content.
    throw ByteOffsetError(path, 0, std::string("libpcap cannot read it: ") + err.data());
  }
  std::unique_ptr<pcap_t, void (*)(pcap_t*)> pcap(raw, &pcap_close);
  const int dlt = pcap_datalink(raw);
  const char* dlt_name = pcap_datalink_val_to_name(dlt);
  stats->format = kind == FileKind::kPcapng ? "pcapng" : "pcap";
  stats->link_type = dlt_name ? dlt_name : std::to_string(dlt);
  switch (dlt) {
    case DLT_EN10MB: case DLT_LINUX_SLL: case DLT_LINUX_SLL2: case DLT_RAW: case DLT_NULL: case DLT_LOOP:
#ifdef DLT_IPV4
    case DLT_IPV4:
#endif
      break;
    default:
      throw ByteOffsetError(path, 0, "link type " + stats->link_type +
                                         " is not one rangekit reads (Ethernet, Linux cooked, raw IP, loopback)");
  }
  PacketReader reader(path, on_datagram, on_problem, stats);
  // pcap: a 24-octet file header, then per packet a 16-octet record header (24 in the "modified" format) and its
  // octets, so each packet's offset is known without asking the FILE. pcapng: the enhanced packet block's data
  // start, exact for blocks without options (the common case); the FILE position after each block.
  const std::uint64_t record_header = kind == FileKind::kPcapModified ? 24 : 16;
  std::uint64_t next = 24;
  std::FILE* file = pcap_file(raw);
  struct pcap_pkthdr* h = nullptr;
  const u_char* data = nullptr;
  std::uint64_t number = 0;
  double last_expiry = -std::numeric_limits<double>::infinity();
  for (;;) {
    const int rc = pcap_next_ex(raw, &h, &data);
    if (rc == PCAP_ERROR_BREAK) break;
    if (rc != 1) {
      on_problem(kind == FileKind::kPcapng || file == nullptr ? 0 : next,
                 std::string("after packet ") + std::to_string(number) + ": " + pcap_geterr(raw));
      break;
    }
    ++number;
    std::uint64_t offset = 0;
    if (kind == FileKind::kPcapng) {
      const long end = file ? std::ftell(file) : -1;
      const std::uint64_t padded = (std::uint64_t{h->caplen} + 3) & ~std::uint64_t{3};
      offset = end > 0 && static_cast<std::uint64_t>(end) >= padded + 4 ? static_cast<std::uint64_t>(end) - 4 - padded : 0;
    } else {
      offset = next + record_header;
      next = offset + h->caplen;
    }
    const double unix_s = static_cast<double>(h->ts.tv_sec) + static_cast<double>(h->ts.tv_usec) * 1e-9;
    reader.Packet(dlt, data, h->caplen, h->len, unix_s, offset, number);
    if (unix_s > last_expiry + 10.0) {  // fragments wait at most 30 s (IP's own reassembly timeout is 15–120 s)
      reader.ExpireFragments(unix_s - 30.0);
      last_expiry = unix_s;
    }
  }
  reader.Finish();
}

}  // namespace

void ReadCapture(const std::string& path, const std::function<void(const Datagram&)>& on_datagram,
                 const CaptureProblem& on_problem, CaptureStats* stats) {
  const FileKind kind = KindOf(path);
  if (kind != FileKind::kRaw) {
    ReadPcap(path, nullptr, kind, on_datagram, on_problem, stats);
    return;
  }
  const std::string bytes = io::ReadFile(path);
  ReadCaptureBuffer(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size(), path, on_datagram, on_problem,
                    stats);
}

void ReadCaptureBuffer(const std::uint8_t* data, std::size_t size, const std::string& name,
                       const std::function<void(const Datagram&)>& on_datagram, const CaptureProblem& on_problem,
                       CaptureStats* stats) {
  const FileKind kind = KindOfMagic(data, size);
  if (kind != FileKind::kRaw) {
    std::FILE* f = fmemopen(const_cast<std::uint8_t*>(data), size, "rb");
    if (f == nullptr) throw IoError(name, std::strerror(errno));
    ReadPcap(name, f, kind, on_datagram, on_problem, stats);
    return;
  }
  stats->format = "raw";
  Datagram d;
  d.data = data;
  d.size = size;
  d.capture_unix_s = std::numeric_limits<double>::quiet_NaN();
  on_datagram(d);
}

std::string EndpointText(std::uint32_t ip, std::uint16_t port) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%u.%u.%u.%u:%u", ip >> 24, (ip >> 16) & 255, (ip >> 8) & 255, ip & 255, port);
  return buf;
}

}  // namespace rk::asterix
