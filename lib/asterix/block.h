// ASTERIX data blocks (CAT, LEN, records...) in a buffer — one UDP datagram, or a whole raw `.ast` record stream
// — walked record by record. A block whose length runs past the buffer, or shorter than its own header, ends the
// buffer (nothing after it can be trusted to start a block); a block of a category rangekit does not decode is
// skipped whole by its length; a record that cannot be walked ends its block (its length is unknown). Each
// problem reaches the visitor with its offset in the buffer and its reason.
#pragma once

#include <cstddef>
#include <cstdint>

#include "asterix/record.h"

namespace rk::asterix {

class BlockVisitor {
 public:
  virtual ~BlockVisitor() = default;
  // A record walked; `offset`: its first octet in the buffer.
  virtual void OnRecord(const RecordLayout& record, std::size_t offset) = 0;
  // A problem at `offset` in the buffer; `category` 0 when the block header itself is bad.
  virtual void OnBad(std::size_t offset, std::uint8_t category, const char* reason) = 0;
};

// Walks every block of data[0, size). Returns the number of blocks whose header was read.
std::size_t WalkBlocks(const std::uint8_t* data, std::size_t size, BlockVisitor* visitor);

}  // namespace rk::asterix
