#include "asterix/block.h"

namespace rk::asterix {

std::size_t WalkBlocks(const std::uint8_t* data, std::size_t size, BlockVisitor* visitor) {
  std::size_t pos = 0, blocks = 0;
  while (pos < size) {
    if (size - pos < 3) {
      visitor->OnBad(pos, 0, "fewer than 3 octets left: not a data block header");
      return blocks;
    }
    const std::uint8_t cat = data[pos];
    const std::size_t length = (std::size_t{data[pos + 1]} << 8) | data[pos + 2];
    if (length < 3) {
      visitor->OnBad(pos, cat, "data block length below 3 octets (its own header)");
      return blocks;
    }
    if (length > size - pos) {
      visitor->OnBad(pos, cat, "data block length runs past the end of the datagram");
      return blocks;
    }
    ++blocks;
    const CategorySpec* spec = FindCategory(cat);
    if (spec == nullptr) {
      visitor->OnBad(pos, cat, "unknown category (rangekit decodes CAT001, CAT034 and CAT048)");
      pos += length;
      continue;
    }
    if (length == 3) {
      visitor->OnBad(pos, cat, "data block without records");
      pos += length;
      continue;
    }
    std::size_t r = pos + 3;
    const std::size_t end = pos + length;
    RecordLayout layout;
    RecordError error;
    while (r < end) {
      if (data[r] == 0) {  // an empty FSPEC: zero padding to the block's end (some encoders pad), else malformed
        std::size_t z = r;
        while (z < end && data[z] == 0) ++z;
        if (z != end) visitor->OnBad(r, cat, "record with an empty FSPEC");
        break;
      }
      if (!WalkRecord(*spec, data + r, end - r, &layout, &error)) {
        visitor->OnBad(r + error.offset, cat, error.reason);
        break;
      }
      visitor->OnRecord(layout, r);
      r += layout.size;
    }
    pos = end;
  }
  return blocks;
}

}  // namespace rk::asterix
