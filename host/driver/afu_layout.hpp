#pragma once
// Byte layout of the shared buffers and the status line (docs/afu-interface.md).
// Pure encode/decode over HostMemory, shared by the driver and test models.
#include <cstdint>
#include <vector>

#include "collide/batch.hpp"
#include "link/host_memory.hpp"

namespace collide::driver {

enum Csr : std::uint8_t {
  kCtrl = 0, kSphereBase = 1, kNumSpheres = 2, kPairBase = 3, kNumPairs = 4,
  kContactBase = 5, kContactCapacity = 6, kStatusAddr = 7, kMode = 8,
};

enum ErrorFlag : std::uint32_t {
  kErrSphereIndex = 1u << 0,     // a sphere index out of range
  kErrTooManySpheres = 1u << 1,  // NUM_SPHERES above the on-chip table
  kErrContactOverflow = 1u << 2, // contact buffer too small
  kErrNonFinite = 1u << 3,       // a non-finite input was seen (informational)
  kErrBadConfig = 1u << 4,       // e.g. base address 0, NUM_PAIRS >= 2^24
};

enum RecordFlag : std::uint8_t {
  kRecHit = 1u << 0,
  // bits 1..2: case
  kRecNonFinite = 1u << 3,
  kRecArithFault = 1u << 4,
};
enum RecordCase : std::uint8_t { kCaseSeparated = 0, kCaseContact = 1, kCaseCoincident = 2, kCaseInvalid = 3 };

struct ContactRecord {
  double px = 0, py = 0, pz = 0, nx = 0, ny = 0, nz = 0, depth = 0;
  std::uint32_t pair = 0;
  std::uint8_t flags = 0;
  bool hit() const { return flags & kRecHit; }
  std::uint8_t recordCase() const { return (flags >> 1) & 3; }
};

struct StatusLine {
  std::uint32_t done = 0, errors = 0, pairsProcessed = 0, contactsFound = 0,
                recordsWritten = 0, nonFinitePairs = 0, firstBadPair = 0xFFFFFFFFu;
  std::uint32_t cyclesTotal = 0, cyclesLoading = 0, cyclesComputing = 0,
                cyclesWaitRead = 0, cyclesWaitWrite = 0;
};

std::uint64_t sphereLines(std::size_t spheres, LinkFormat f);
std::uint64_t pairLines(std::size_t pairs);
std::uint64_t contactLines(std::size_t records, LinkFormat f);
unsigned recordsPerLine(LinkFormat f);

void writeSphereTable(link::HostMemory& m, std::uint64_t base, const SphereTable& s, LinkFormat f);
void writePairList(link::HostMemory& m, std::uint64_t base, const PairList& p);
ContactRecord readContact(const link::HostMemory& m, std::uint64_t base, std::size_t n, LinkFormat f);
void writeContact(link::HostMemory& m, std::uint64_t base, std::size_t n, LinkFormat f,
                  const ContactRecord& c);
StatusLine readStatus(const link::HostMemory& m, std::uint64_t addr);
link::Line encodeStatus(const StatusLine& s);

// Decoding helpers for line images (what a model AFU receives on rdResp).
void sphereFromLine(const link::Line& l, unsigned slot, LinkFormat f, double out[4]);
void pairFromLine(const link::Line& l, unsigned slot, std::uint16_t& i, std::uint16_t& j);
void contactToLine(link::Line& l, unsigned slot, LinkFormat f, const ContactRecord& c);

}  // namespace collide::driver
