#include "driver/afu_layout.hpp"

#include <cstring>
#include <stdexcept>

namespace collide::driver {

using link::HostMemory;
using link::Line;

namespace {
template <typename T>
void put(Line& l, std::size_t byte, T v) { std::memcpy(l.data() + byte, &v, sizeof(T)); }
template <typename T>
T get(const Line& l, std::size_t byte) {
  T v;
  std::memcpy(&v, l.data() + byte, sizeof(T));
  return v;
}
unsigned spheresPerLine(LinkFormat f) { return f == LinkFormat::Binary32 ? 4 : 2; }
}  // namespace

unsigned recordsPerLine(LinkFormat f) { return f == LinkFormat::Binary32 ? 2 : 1; }
std::uint64_t sphereLines(std::size_t s, LinkFormat f) { return (s + spheresPerLine(f) - 1) / spheresPerLine(f); }
std::uint64_t pairLines(std::size_t p) { return (p + 15) / 16; }
std::uint64_t contactLines(std::size_t r, LinkFormat f) { return (r + recordsPerLine(f) - 1) / recordsPerLine(f); }

void writeSphereTable(HostMemory& m, std::uint64_t base, const SphereTable& s, LinkFormat f) {
  const unsigned per = spheresPerLine(f);
  for (std::size_t k = 0; k < s.size(); ++k) {
    Line& l = m.line(base + k / per);
    const std::size_t off = (k % per) * (f == LinkFormat::Binary32 ? 16 : 32);
    const double v[4] = {s.x[k], s.y[k], s.z[k], s.r[k]};
    for (int c = 0; c < 4; ++c) {
      if (f == LinkFormat::Binary32) put(l, off + 4 * c, static_cast<float>(v[c]));
      else put(l, off + 8 * c, v[c]);
    }
  }
}

void writePairList(HostMemory& m, std::uint64_t base, const PairList& p) {
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.i[k] > 0xFFFF || p.j[k] > 0xFFFF)
      throw std::out_of_range("pair " + std::to_string(k) + ": sphere index above 65535 (u16 on the link)");
    Line& l = m.line(base + k / 16);
    put(l, 4 * (k % 16), static_cast<std::uint16_t>(p.i[k]));
    put(l, 4 * (k % 16) + 2, static_cast<std::uint16_t>(p.j[k]));
  }
}

void sphereFromLine(const Line& l, unsigned slot, LinkFormat f, double out[4]) {
  for (int c = 0; c < 4; ++c)
    out[c] = f == LinkFormat::Binary32 ? get<float>(l, 16 * slot + 4 * c) : get<double>(l, 32 * slot + 8 * c);
}

void pairFromLine(const Line& l, unsigned slot, std::uint16_t& i, std::uint16_t& j) {
  i = get<std::uint16_t>(l, 4 * slot);
  j = get<std::uint16_t>(l, 4 * slot + 2);
}

void contactToLine(Line& l, unsigned slot, LinkFormat f, const ContactRecord& c) {
  const double v[7] = {c.px, c.py, c.pz, c.nx, c.ny, c.nz, c.depth};
  if (f == LinkFormat::Binary32) {
    const std::size_t off = 32 * slot;
    for (int k = 0; k < 7; ++k) put(l, off + 4 * k, static_cast<float>(v[k]));
    put(l, off + 28, (c.pair & 0xFFFFFFu) | (std::uint32_t{c.flags} << 24));
  } else {
    for (int k = 0; k < 7; ++k) put(l, 8 * k, v[k]);
    put(l, 56, c.pair);
    put(l, 60, std::uint32_t{c.flags});
  }
}

ContactRecord readContact(const HostMemory& m, std::uint64_t base, std::size_t n, LinkFormat f) {
  const unsigned per = recordsPerLine(f);
  const Line& l = m.line(base + n / per);
  ContactRecord c;
  double* v[7] = {&c.px, &c.py, &c.pz, &c.nx, &c.ny, &c.nz, &c.depth};
  if (f == LinkFormat::Binary32) {
    const std::size_t off = 32 * (n % per);
    for (int k = 0; k < 7; ++k) *v[k] = get<float>(l, off + 4 * k);
    const auto w = get<std::uint32_t>(l, off + 28);
    c.pair = w & 0xFFFFFFu;
    c.flags = static_cast<std::uint8_t>(w >> 24);
  } else {
    for (int k = 0; k < 7; ++k) *v[k] = get<double>(l, 8 * k);
    c.pair = get<std::uint32_t>(l, 56);
    c.flags = static_cast<std::uint8_t>(get<std::uint32_t>(l, 60));
  }
  return c;
}

void writeContact(HostMemory& m, std::uint64_t base, std::size_t n, LinkFormat f, const ContactRecord& c) {
  contactToLine(m.line(base + n / recordsPerLine(f)), static_cast<unsigned>(n % recordsPerLine(f)), f, c);
}

StatusLine readStatus(const HostMemory& m, std::uint64_t addr) {
  const Line& l = m.line(addr);
  StatusLine s;
  std::uint32_t* f[] = {&s.done, &s.errors, &s.pairsProcessed, &s.contactsFound, &s.recordsWritten,
                        &s.nonFinitePairs, &s.firstBadPair};
  for (int k = 0; k < 7; ++k) *f[k] = get<std::uint32_t>(l, 4 * k);
  std::uint32_t* c[] = {&s.cyclesTotal, &s.cyclesLoading, &s.cyclesComputing, &s.cyclesWaitRead,
                        &s.cyclesWaitWrite};
  for (int k = 0; k < 5; ++k) *c[k] = get<std::uint32_t>(l, 32 + 4 * k);
  return s;
}

Line encodeStatus(const StatusLine& s) {
  Line l{};
  const std::uint32_t f[] = {s.done, s.errors, s.pairsProcessed, s.contactsFound, s.recordsWritten,
                             s.nonFinitePairs, s.firstBadPair};
  for (int k = 0; k < 7; ++k) put(l, 4 * k, f[k]);
  const std::uint32_t c[] = {s.cyclesTotal, s.cyclesLoading, s.cyclesComputing, s.cyclesWaitRead,
                             s.cyclesWaitWrite};
  for (int k = 0; k < 5; ++k) put(l, 32 + 4 * k, c[k]);
  return l;
}

}  // namespace collide::driver
