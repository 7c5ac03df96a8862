// Where ASTERIX arrives from: a network capture (pcap or pcapng, read by libpcap: Ethernet with VLAN tags, Linux
// cooked v1/v2, raw IP, BSD loopback; IPv4 UDP, fragmented datagrams reassembled) or a raw record stream (`.ast`:
// data blocks back to back). The file's first octets decide, not its name; a name that says pcap on a file that
// is not one is refused. Each UDP payload (or the whole raw stream) reaches the caller with its capture time and
// its offset in the file, so every message can name the byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>

namespace rk::asterix {

struct Datagram {
  const std::uint8_t* data = nullptr;  // the UDP payload, or the whole raw stream
  std::size_t size = 0;
  double capture_unix_s = 0.0;  // the capture's time stamp (UTC, s since 1970); NaN for a raw stream
  std::uint64_t file_offset = 0;  // of data[0] in the file (a reassembled datagram: of its first fragment's payload)
  bool reassembled = false;       // from IP fragments: offsets past the first fragment are not file offsets
  std::uint64_t packet = 0;       // 1-based packet number in the capture (the last fragment's); 0 for a raw stream
  std::uint32_t src_ip = 0, dst_ip = 0;  // host order; 0 for a raw stream
  std::uint16_t src_port = 0, dst_port = 0;
};

struct CaptureStats {
  std::string format;     // "pcap", "pcapng", "raw"
  std::string link_type;  // libpcap's name of the capture's link type ("EN10MB"); empty for a raw stream
  std::uint64_t packets = 0;
  std::uint64_t udp_datagrams = 0;
  std::uint64_t other_packets = 0;        // not IPv4 UDP (ARP, IPv6, TCP, ...): skipped
  std::uint64_t fragments = 0;            // IPv4 fragments seen
  std::uint64_t reassembled = 0;          // datagrams rebuilt from them
  std::uint64_t incomplete_datagrams = 0;  // fragments that never completed a datagram (lost, or beyond the file)
  std::uint64_t truncated_packets = 0;    // cut by the capture's snap length
};

// A problem in the capture itself (a truncated packet, a bad IP or UDP header, a truncated file): its byte
// offset in the file and the reason.
using CaptureProblem = std::function<void(std::uint64_t file_offset, const std::string& reason)>;

// Reads `path` and calls `on_datagram` for every UDP payload (or once for a raw stream). IoError (exit 4) when it
// cannot be read; ByteOffsetError (exit 3) for a file named .pcap/.pcapng/.cap that is not one, or whose link type
// rangekit cannot read; every other problem goes to `on_problem` and the reading goes on.
void ReadCapture(const std::string& path, const std::function<void(const Datagram&)>& on_datagram,
                 const CaptureProblem& on_problem, CaptureStats* stats);

// The same over octets in memory (`name` in messages): a capture when they start with a capture's magic number, else
// a raw stream. For the fuzz harness (tests/fuzz/fuzz_asterix_capture.cc).
void ReadCaptureBuffer(const std::uint8_t* data, std::size_t size, const std::string& name,
                       const std::function<void(const Datagram&)>& on_datagram, const CaptureProblem& on_problem,
                       CaptureStats* stats);

// "10.17.58.184:21124".
std::string EndpointText(std::uint32_t ip, std::uint16_t port);

}  // namespace rk::asterix
