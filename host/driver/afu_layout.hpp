#pragma once
// Byte layout of the shared buffers and the status line (docs/afu-interface.md), over
// HostMemory, shared by the driver and the test models. Every offset, bit and code comes
// from the generated contract header (generated/afu_contract.hpp), never a literal here.
#include <cstdint>
#include <vector>

#include "afu_contract.hpp"
#include "collide/batch.hpp"
#include "link/host_memory.hpp"

namespace collide::driver {

// One AFU configuration's buffers: the link format and the record layout.
struct BufferLayout {
  LinkFormat format = LinkFormat::Binary32;
  std::uint32_t records = contract::LAYOUT_FULL;  // contract::LAYOUT_*

  bool derived() const { return records == contract::LAYOUT_DERIVED; }
  unsigned fieldBytes() const { return collide::fieldBytes(format); }
  unsigned sphereBytes() const { return contract::SPHERE_FIELDS * fieldBytes(); }
  unsigned spheresPerLine() const { return contract::LINE_BYTES / sphereBytes(); }
  unsigned valueFields() const;  // 7 (full) or 2 (derived)
  unsigned recordBytes() const { return valueFields() * fieldBytes() + contract::TAG_BYTES; }
  unsigned recordsPerLine() const { return contract::LINE_BYTES / recordBytes(); }
  // Where record n lives. Compact: line n / R, slot n % R. Dense (record n = pair n): each
  // pair line's records start a contact line, since pair lines are computed in the order
  // they arrive: line (n / 16) * ceil(16 / R) + (n % 16) / R, slot (n % 16) % R.
  std::uint64_t recordLine(std::size_t n, bool dense) const;
  unsigned recordSlot(std::size_t n, bool dense) const;
};

// A record as the AFU wrote it: full records fill px..depth, derived ones d and w (the
// driver then rebuilds px..depth, see contact_rebuild.hpp).
struct ContactRecord {
  double px = 0, py = 0, pz = 0, nx = 0, ny = 0, nz = 0, depth = 0;
  double d = 0, w = 0;
  std::uint32_t pair = 0;
  std::uint8_t flags = 0;
  bool hit() const { return flags & contract::REC_HIT; }
  std::uint8_t recordCase() const { return (flags >> contract::REC_KIND_SHIFT) & contract::REC_KIND_MASK; }
};

struct StatusLine {
  std::uint32_t done = 0, errors = 0, pairsProcessed = 0, contactsFound = 0,
                recordsWritten = 0, nonFinitePairs = 0, firstBadPair = contract::NO_BAD_PAIR;
  std::uint32_t cyclesTotal = 0, cyclesLoading = 0, cyclesComputing = 0,
                cyclesWaitRead = 0, cyclesWaitWrite = 0;
};

std::uint64_t sphereLines(std::size_t spheres, LinkFormat f);
std::uint64_t pairLines(std::size_t pairs);
// Lines of a contact buffer for `records` records.
std::uint64_t contactLines(std::size_t records, const BufferLayout& l, bool dense);

// Writes the table in the link format (one RNE rounding from double). Returns, per sphere,
// whether a value did not fit: a finite value that became infinite, or a positive radius
// that became zero (the caller flags its pairs, contract::REC_HOST_RANGE).
std::vector<std::uint8_t> writeSphereTable(link::HostMemory& m, std::uint64_t base, const SphereTable& s,
                                           LinkFormat f);
// Sphere k of the table as the link carries it (x, y, z, r).
void linkSphere(const SphereTable& s, std::size_t k, LinkFormat f, double out[4]);
void writePairList(link::HostMemory& m, std::uint64_t base, const PairList& p);
ContactRecord readContact(const link::HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& l,
                          bool dense);
void writeContact(link::HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& l, bool dense,
                  const ContactRecord& c);
StatusLine readStatus(const link::HostMemory& m, std::uint64_t addr);
link::Line encodeStatus(const StatusLine& s);

// Decoding helpers for line images (what a model AFU receives on rdResp).
void sphereFromLine(const link::Line& l, unsigned slot, LinkFormat f, double out[4]);
void pairFromLine(const link::Line& l, unsigned slot, std::uint16_t& i, std::uint16_t& j);
void contactToLine(link::Line& l, unsigned slot, const BufferLayout& lay, const ContactRecord& c);

}  // namespace collide::driver
