#pragma once
// Byte layout of the shared buffers and the status line (docs/afu-interface.md), over
// HostMemory, shared by the driver and the test models. Every offset, bit and code comes
// from the generated contract header (generated/afu_contract.hpp), never a literal here.
#include <cmath>
#include <cstdint>
#include <vector>

#include "afu_contract.hpp"
#include "batch/batch.hpp"
#include "link/host_memory.hpp"

namespace collide::driver {

// One AFU configuration's buffers: the link format and the record layout.
struct BufferLayout {
  LinkFormat format = LinkFormat::Binary32;
  std::uint32_t records = contract::LAYOUT_FULL;  // contract::LAYOUT_*

  // d and w instead of the contact (the driver rebuilds it, contact_rebuild.hpp)
  bool derived() const { return records == contract::LAYOUT_DERIVED || records == contract::LAYOUT_DERIVED_MASKED; }
  // no pair index in a record: its position names it (compact: mask headers)
  bool masked() const { return records == contract::LAYOUT_FULL_MASKED || records == contract::LAYOUT_DERIVED_MASKED; }
  unsigned fieldBytes() const { return collide::fieldBytes(format); }
  unsigned sphereBytes() const { return contract::SPHERE_FIELDS * fieldBytes(); }
  unsigned spheresPerLine() const { return contract::LINE_BYTES / sphereBytes(); }
  unsigned valueFields() const;  // 7 (full) or 2 (derived)
  unsigned tagBytes() const { return masked() ? 1 : contract::TAG_BYTES; }  // the tag word, or the flags byte
  unsigned recordBytes() const { return valueFields() * fieldBytes() + tagBytes(); }
  unsigned recordsPerLine() const { return contract::LINE_BYTES / recordBytes(); }
  // Compact slots `hits` contacts can take: masked adds a header per group with a hit.
  std::size_t compactSlotsFor(std::size_t hits) const { return masked() ? 2 * hits : hits; }
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
  // A miss with a non-finite input or an arithmetic fault: in pair mode a record in compact
  // mode too, so that its flag reaches the user (docs/afu-interface.md).
  bool flaggedMiss() const { return !hit() && (flags & (contract::REC_NONFINITE | contract::REC_ARITH)); }
  std::uint8_t recordCase() const { return (flags >> contract::REC_KIND_SHIFT) & contract::REC_KIND_MASK; }
};

// A masked layout's compact slot before a group's records: bit k of `mask` set when pair
// first + k has a record (a hit, or in pair mode a miss with NONFINITE or ARITH).
struct MaskHeader {
  std::uint32_t first = 0;
  std::uint32_t mask = 0;
};

struct StatusLine {
  std::uint32_t done = 0, errors = 0, pairsProcessed = 0, contactsFound = 0,
                recordsWritten = 0, nonFinitePairs = 0, firstBadPair = contract::NO_BAD_PAIR;
  std::uint32_t flaggedMisses = 0;  // misses with NONFINITE or ARITH: pair mode writes them in compact mode too
  std::uint32_t cyclesTotal = 0, cyclesLoading = 0, cyclesComputing = 0,
                cyclesWaitRead = 0, cyclesWaitWrite = 0;
  // World mode: the broad phase's cycles, its cell level L (a signed i32, cellEdge(L)) and
  // the spheres too large for the cell (0 in pair mode).
  std::uint32_t cyclesBroad = 0, worldCellLevel = 0, worldLarge = 0;
};

// The edge of the broad phase's cells at level L: 2^(L/2) for even L, 1.5 * 2^((L-1)/2) for
// odd L (the status line's WORLD_CELL_LEVEL).
inline double cellEdge(std::int32_t level) {
  const std::int32_t half = level >= 0 ? level / 2 : -((1 - level) / 2);  // floor(L / 2)
  return (level % 2 == 0 ? 1.0 : 1.5) * std::ldexp(1.0, half);
}

// World mode: a record's pair field names its spheres, i in the low TAG_WORLD_INDEX_BITS
// bits and j above them.
inline std::uint32_t worldPairI(std::uint32_t pair) { return pair & ((1u << contract::TAG_WORLD_INDEX_BITS) - 1); }
inline std::uint32_t worldPairJ(std::uint32_t pair) { return pair >> contract::TAG_WORLD_INDEX_BITS; }

std::uint64_t sphereLines(std::size_t spheres, LinkFormat f);
std::uint64_t pairLines(std::size_t pairs);
// Lines of a contact buffer for `records` records.
std::uint64_t contactLines(std::size_t records, const BufferLayout& l, bool dense);

// Writes the table in the link format (one RNE rounding from double). Returns, per sphere,
// whether a value did not fit: a finite value that became infinite, or a positive radius
// that became zero (the caller flags its pairs, contract::REC_HOST_RANGE).
std::vector<std::uint8_t> writeSphereTable(link::HostMemory& m, std::uint64_t base, const SphereTable& s,
                                           LinkFormat f);
// Sphere k of the table as the link carries it (x, y, z, r). Returns whether a value did not
// fit: a finite value that became infinite, or a positive radius that became zero (its pairs
// get contract::REC_HOST_RANGE).
bool linkSphere(const SphereTable& s, std::size_t k, LinkFormat f, double out[4]);
void writePairList(link::HostMemory& m, std::uint64_t base, const PairList& p);
// Slot n of a contact buffer. A masked record has no pair index: `pair` is what the caller
// knows of it (dense: n, which is the default).
ContactRecord readContact(const link::HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& l,
                          bool dense, std::int64_t pair = -1);
void writeContact(link::HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& l, bool dense,
                  const ContactRecord& c);
MaskHeader readMaskHeader(const link::HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& l);
void writeMaskHeader(link::HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& l, const MaskHeader& h);

// The `written` slots of a run's buffer as records, pair indices filled in. Masked compact
// buffers are read header by header (a truncated buffer may end inside a group); a header
// naming a pair at or past `numPairs`, with an empty mask or bits beyond the mask, is
// corrupt: std::runtime_error naming the slot.
struct DecodedRecords {
  std::vector<ContactRecord> records;
  std::size_t headers = 0;
};
DecodedRecords readRecords(const link::HostMemory& m, std::uint64_t base, std::size_t written, const BufferLayout& l,
                           bool dense, std::size_t numPairs);
StatusLine readStatus(const link::HostMemory& m, std::uint64_t addr);
link::Line encodeStatus(const StatusLine& s);

// Decoding helpers for line images (what a model AFU receives on rdResp).
void sphereFromLine(const link::Line& l, unsigned slot, LinkFormat f, double out[4]);
void pairFromLine(const link::Line& l, unsigned slot, std::uint16_t& i, std::uint16_t& j);
void contactToLine(link::Line& l, unsigned slot, const BufferLayout& lay, const ContactRecord& c);

}  // namespace collide::driver
