#include "driver/afu_layout.hpp"

#include <cmath>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string>

namespace collide::driver {

using link::HostMemory;
using link::Line;
namespace c = contract;

namespace {
template <typename T>
void put(Line& l, std::size_t byte, T v) { std::memcpy(l.data() + byte, &v, sizeof(T)); }
template <typename T>
T get(const Line& l, std::size_t byte) {
  T v;
  std::memcpy(&v, l.data() + byte, sizeof(T));
  return v;
}

// One link field: the value's bit pattern in the link format, little-endian.
void putField(Line& l, std::size_t byte, LinkFormat f, double v) {
  switch (f) {
    case LinkFormat::Binary16:
    case LinkFormat::BFloat16: put(l, byte, static_cast<std::uint16_t>(format::encode(v, numberFormat(f)))); break;
    case LinkFormat::Binary32: put(l, byte, static_cast<float>(v)); break;
    case LinkFormat::Binary64: put(l, byte, v); break;
  }
}
double getField(const Line& l, std::size_t byte, LinkFormat f) {
  switch (f) {
    case LinkFormat::Binary16:
    case LinkFormat::BFloat16: return format::decode(get<std::uint16_t>(l, byte), numberFormat(f));
    case LinkFormat::Binary32: return get<float>(l, byte);
    case LinkFormat::Binary64: return get<double>(l, byte);
  }
  return 0;
}
double& valueRef(ContactRecord& r, const BufferLayout& lay, unsigned k) {
  double* full[7] = {&r.px, &r.py, &r.pz, &r.nx, &r.ny, &r.nz, &r.depth};
  double* derived[2] = {&r.d, &r.w};
  return lay.derived() ? *derived[k] : *full[k];
}
}  // namespace

unsigned BufferLayout::valueFields() const {
  return derived() ? static_cast<unsigned>(std::size(c::kDerivedFields)) : static_cast<unsigned>(std::size(c::kFullFields));
}

std::uint64_t sphereLines(std::size_t s, LinkFormat f) {
  const unsigned per = BufferLayout{f}.spheresPerLine();
  return (s + per - 1) / per;
}
std::uint64_t pairLines(std::size_t p) { return (p + c::PAIRS_PER_LINE - 1) / c::PAIRS_PER_LINE; }
std::uint64_t BufferLayout::recordLine(std::size_t n, bool dense) const {
  const unsigned per = recordsPerLine();
  if (!dense) return n / per;
  const unsigned perPairLine = (c::PAIRS_PER_LINE + per - 1) / per;
  return (n / c::PAIRS_PER_LINE) * perPairLine + (n % c::PAIRS_PER_LINE) / per;
}
unsigned BufferLayout::recordSlot(std::size_t n, bool dense) const {
  const unsigned per = recordsPerLine();
  return static_cast<unsigned>(dense ? (n % c::PAIRS_PER_LINE) % per : n % per);
}
std::uint64_t contactLines(std::size_t r, const BufferLayout& l, bool dense) {
  return r == 0 ? 0 : l.recordLine(r - 1, dense) + 1;
}

bool linkSphere(const SphereTable& s, std::size_t k, LinkFormat f, double out[4]) {
  const auto nf = numberFormat(f);
  const double v[4] = {s.x[k], s.y[k], s.z[k], s.r[k]};
  bool outside = false;
  for (int i = 0; i < 4; ++i) {
    out[i] = format::roundTo(v[i], nf);
    outside = outside || (std::isfinite(v[i]) && !std::isfinite(out[i]));
  }
  return outside || (v[3] > 0 && out[3] == 0);
}

std::vector<std::uint8_t> writeSphereTable(HostMemory& m, std::uint64_t base, const SphereTable& s, LinkFormat f) {
  const BufferLayout lay{f};
  const unsigned per = lay.spheresPerLine(), fb = lay.fieldBytes();
  std::vector<std::uint8_t> outOfRange(s.size(), 0);
  for (std::size_t k = 0; k < s.size(); ++k) {
    Line& l = m.line(base + k / per);
    const std::size_t off = (k % per) * lay.sphereBytes();
    double q[4];
    outOfRange[k] = linkSphere(s, k, f, q);
    for (int i = 0; i < 4; ++i) putField(l, off + fb * i, f, q[i]);
  }
  return outOfRange;
}

void writePairList(HostMemory& m, std::uint64_t base, const PairList& p) {
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.i[k] > 0xFFFF || p.j[k] > 0xFFFF)
      throw std::out_of_range("pair " + std::to_string(k) + ": sphere index above 65535 (u16 on the link)");
    Line& l = m.line(base + k / c::PAIRS_PER_LINE);
    const std::size_t off = c::PAIR_BYTES * (k % c::PAIRS_PER_LINE);
    put(l, off, static_cast<std::uint16_t>(p.i[k]));
    put(l, off + 2, static_cast<std::uint16_t>(p.j[k]));
  }
}

void sphereFromLine(const Line& l, unsigned slot, LinkFormat f, double out[4]) {
  const BufferLayout lay{f};
  for (unsigned i = 0; i < 4; ++i) out[i] = getField(l, slot * lay.sphereBytes() + i * lay.fieldBytes(), f);
}

void pairFromLine(const Line& l, unsigned slot, std::uint16_t& i, std::uint16_t& j) {
  i = get<std::uint16_t>(l, c::PAIR_BYTES * slot);
  j = get<std::uint16_t>(l, c::PAIR_BYTES * slot + 2);
}

void contactToLine(Line& l, unsigned slot, const BufferLayout& lay, const ContactRecord& r) {
  const std::size_t off = std::size_t{slot} * lay.recordBytes();
  ContactRecord copy = r;
  for (unsigned k = 0; k < lay.valueFields(); ++k) putField(l, off + k * lay.fieldBytes(), lay.format, valueRef(copy, lay, k));
  const std::size_t tag = off + lay.valueFields() * lay.fieldBytes();
  const std::uint32_t pairMask = (std::uint32_t{1} << c::TAG_PAIR_BITS) - 1;
  if (lay.masked()) put(l, tag, r.flags);
  else put(l, tag, (r.pair & pairMask) | (std::uint32_t{r.flags} << c::TAG_FLAGS_SHIFT));
}

ContactRecord readContact(const HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& lay, bool dense,
                          std::int64_t pair) {
  const Line& l = m.line(base + lay.recordLine(n, dense));
  const std::size_t off = std::size_t{lay.recordSlot(n, dense)} * lay.recordBytes();
  ContactRecord r;
  for (unsigned k = 0; k < lay.valueFields(); ++k) valueRef(r, lay, k) = getField(l, off + k * lay.fieldBytes(), lay.format);
  const std::size_t tagAt = off + lay.valueFields() * lay.fieldBytes();
  if (lay.masked()) {
    r.pair = static_cast<std::uint32_t>(pair >= 0 ? pair : static_cast<std::int64_t>(n));
    r.flags = get<std::uint8_t>(l, tagAt);
  } else {
    const auto tag = get<std::uint32_t>(l, tagAt);
    r.pair = tag & ((std::uint32_t{1} << c::TAG_PAIR_BITS) - 1);
    r.flags = static_cast<std::uint8_t>(tag >> c::TAG_FLAGS_SHIFT);
  }
  return r;
}

void writeContact(HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& lay, bool dense,
                  const ContactRecord& r) {
  contactToLine(m.line(base + lay.recordLine(n, dense)), lay.recordSlot(n, dense), lay, r);
}

namespace {
static_assert(c::HEADER_BITS <= 64, "a mask header's bits fit a u64");
// The header in slot n, and whether any bit of its slot past the header's bits is set.
MaskHeader headerAt(const HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& lay, bool& beyond) {
  const Line& l = m.line(base + lay.recordLine(n, false));
  const std::size_t off = std::size_t{lay.recordSlot(n, false)} * lay.recordBytes();
  std::uint64_t v = 0;
  const unsigned bytes = (c::HEADER_BITS + 7) / 8;
  for (unsigned b = 0; b < bytes; ++b) v |= std::uint64_t{l[off + b]} << (8 * b);
  beyond = (v >> c::HEADER_BITS) != 0;
  for (unsigned b = bytes; b < lay.recordBytes(); ++b) beyond = beyond || l[off + b] != 0;
  MaskHeader h;
  h.first = static_cast<std::uint32_t>((v >> c::HEADER_PAIR_SHIFT) & ((std::uint64_t{1} << c::HEADER_PAIR_BITS) - 1));
  h.mask = static_cast<std::uint32_t>((v >> c::HEADER_MASK_SHIFT) & ((std::uint64_t{1} << c::HEADER_MASK_BITS) - 1));
  return h;
}
}  // namespace

MaskHeader readMaskHeader(const HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& lay) {
  bool beyond = false;
  return headerAt(m, base, n, lay, beyond);
}

void writeMaskHeader(HostMemory& m, std::uint64_t base, std::size_t n, const BufferLayout& lay, const MaskHeader& h) {
  Line& l = m.line(base + lay.recordLine(n, false));
  const std::size_t off = std::size_t{lay.recordSlot(n, false)} * lay.recordBytes();
  const std::uint64_t v = (std::uint64_t{h.first} << c::HEADER_PAIR_SHIFT) | (std::uint64_t{h.mask} << c::HEADER_MASK_SHIFT);
  for (unsigned b = 0; b < lay.recordBytes(); ++b) l[off + b] = b < 8 ? static_cast<std::uint8_t>(v >> (8 * b)) : 0;
}

DecodedRecords readRecords(const HostMemory& m, std::uint64_t base, std::size_t written, const BufferLayout& lay,
                           bool dense, std::size_t numPairs) {
  DecodedRecords out;
  out.records.reserve(written);
  if (!lay.masked() || dense) {
    for (std::size_t k = 0; k < written; ++k) out.records.push_back(readContact(m, base, k, lay, dense));
    return out;
  }
  for (std::size_t slot = 0; slot < written;) {
    bool beyond = false;
    const MaskHeader h = headerAt(m, base, slot, lay, beyond);
    const auto where = "contact slot " + std::to_string(slot) + ": mask header (first pair " + std::to_string(h.first) + ")";
    if (beyond) throw std::runtime_error(where + " has bits set past its mask");
    if (h.mask == 0) throw std::runtime_error(where + " has an empty mask");
    ++out.headers;
    ++slot;
    for (unsigned k = 0; k < c::HEADER_MASK_BITS && slot < written; ++k) {
      if (!(h.mask >> k & 1)) continue;
      const std::size_t pair = std::size_t{h.first} + k;
      if (pair >= numPairs)
        throw std::runtime_error(where + " names pair " + std::to_string(pair) + " of " + std::to_string(numPairs));
      out.records.push_back(readContact(m, base, slot++, lay, false, static_cast<std::int64_t>(pair)));
    }
  }
  return out;
}

namespace {
// The status line's fields, each at its contract offset.
template <typename S, typename F>
void eachStatusField(S& s, F&& f) {
  f(c::STATUS_DONE, s.done); f(c::STATUS_ERROR_FLAGS, s.errors); f(c::STATUS_PAIRS_PROCESSED, s.pairsProcessed);
  f(c::STATUS_CONTACTS_FOUND, s.contactsFound); f(c::STATUS_RECORDS_WRITTEN, s.recordsWritten);
  f(c::STATUS_NONFINITE_PAIRS, s.nonFinitePairs); f(c::STATUS_FIRST_BAD_PAIR, s.firstBadPair);
  f(c::STATUS_FLAGGED_MISSES, s.flaggedMisses);
  f(c::STATUS_CYCLES_TOTAL, s.cyclesTotal); f(c::STATUS_CYCLES_LOAD, s.cyclesLoading);
  f(c::STATUS_CYCLES_COMPUTE, s.cyclesComputing); f(c::STATUS_CYCLES_WAIT_RD, s.cyclesWaitRead);
  f(c::STATUS_CYCLES_WAIT_WR, s.cyclesWaitWrite); f(c::STATUS_CYCLES_BROAD, s.cyclesBroad);
  f(c::STATUS_WORLD_CELL_LEVEL, s.worldCellLevel); f(c::STATUS_WORLD_LARGE, s.worldLarge);
}
}  // namespace

StatusLine readStatus(const HostMemory& m, std::uint64_t addr) {
  const Line& l = m.line(addr);
  StatusLine s;
  eachStatusField(s, [&](std::uint32_t off, std::uint32_t& v) { v = get<std::uint32_t>(l, off); });
  return s;
}

Line encodeStatus(const StatusLine& s) {
  Line l{};
  eachStatusField(s, [&](std::uint32_t off, const std::uint32_t& v) { put(l, off, v); });
  return l;
}

}  // namespace collide::driver
