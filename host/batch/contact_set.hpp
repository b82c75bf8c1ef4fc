#pragma once
// Dense per-pair collision results, structure-of-arrays. Entry k belongs to pair k.
// Values are stored as double; a binary32 backend stores its floats exactly
// (float -> double is exact), so `format` tells how to print them back.
#include <cstdint>
#include <vector>

#include "batch/batch.hpp"

namespace collide {

struct ContactSet {
  LinkFormat format = LinkFormat::Binary64;
  std::vector<std::uint8_t> hit;  // 1: contact (d <= r1 + r2, depth >= 0)
  std::vector<double> px, py, pz, nx, ny, nz, depth;  // zero where hit == 0
  // The record flags of docs/afu-interface.md (contract::REC_*): the AFU's own for rtl, with
  // REC_HOST_RANGE where an input did not fit the link format. The CPU backends leave them
  // zero or empty on their hot path; setCpuRecordFlags (contact_flags.hpp) fills them.
  std::vector<std::uint8_t> flags;

  std::size_t size() const { return hit.size(); }
  std::size_t hits() const;
  void resize(std::size_t n);  // and zero everything
  // Size n without clearing the entries kept: for a writer that sets every entry.
  void resizeForOverwrite(std::size_t n);
  // Entry k of src into entry `to` (which exists) / onto the end. Flags are copied when src
  // has them (a backend that sets none leaves them empty).
  void setEntry(std::size_t to, const ContactSet& src, std::size_t k);
  void appendEntry(const ContactSet& src, std::size_t k);
};

}  // namespace collide
