// The generated contract (generated/afu_contract.hpp) is what the decoders use: a status
// line and records built only from the header's offsets and bits must decode field by
// field, so a consumer that hard-codes an offset the header defines fails here.
#include <gtest/gtest.h>

#include <cstring>

#include "afu_contract.hpp"
#include "driver/afu_layout.hpp"
#include "driver/afu_driver.hpp"

using namespace collide;
using namespace collide::driver;

namespace {
template <typename T>
void put(link::Line& l, std::size_t byte, T v) { std::memcpy(l.data() + byte, &v, sizeof v); }
}  // namespace

TEST(Contract, AStatusLineBuiltFromTheHeadersOffsetsDecodesFieldByField) {
  link::Line l{};
  const std::uint32_t offs[] = {contract::STATUS_DONE, contract::STATUS_ERROR_FLAGS, contract::STATUS_PAIRS_PROCESSED,
                                contract::STATUS_CONTACTS_FOUND, contract::STATUS_RECORDS_WRITTEN,
                                contract::STATUS_NONFINITE_PAIRS, contract::STATUS_FIRST_BAD_PAIR,
                                contract::STATUS_FLAGGED_MISSES, contract::STATUS_CYCLES_TOTAL, contract::STATUS_CYCLES_LOAD,
                                contract::STATUS_CYCLES_COMPUTE, contract::STATUS_CYCLES_WAIT_RD,
                                contract::STATUS_CYCLES_WAIT_WR, contract::STATUS_CYCLES_BROAD,
                                contract::STATUS_WORLD_CELL_LEVEL, contract::STATUS_WORLD_LARGE};
  for (std::uint32_t k = 0; k < std::size(offs); ++k) put<std::uint32_t>(l, offs[k], 1000 + k);
  link::HostMemory m;
  const auto a = m.allocate(1);
  m.line(a.base) = l;
  const StatusLine s = readStatus(m, a.base);
  const std::uint32_t got[] = {s.done, s.errors, s.pairsProcessed, s.contactsFound, s.recordsWritten,
                               s.nonFinitePairs, s.firstBadPair, s.flaggedMisses, s.cyclesTotal, s.cyclesLoading,
                               s.cyclesComputing, s.cyclesWaitRead, s.cyclesWaitWrite, s.cyclesBroad,
                               s.worldCellLevel, s.worldLarge};
  for (std::uint32_t k = 0; k < std::size(offs); ++k) EXPECT_EQ(got[k], 1000 + k) << "status field at byte " << offs[k];
  EXPECT_EQ(encodeStatus(s), l);
}

TEST(Contract, TheWorldCellLevelNamesEdgesOfTwoToTheKAndOneAndAHalfTimesThat) {
  EXPECT_EQ(cellEdge(0), 1.0);
  EXPECT_EQ(cellEdge(1), 1.5);
  EXPECT_EQ(cellEdge(2), 2.0);
  EXPECT_EQ(cellEdge(3), 3.0);
  EXPECT_EQ(cellEdge(-1), 0.75);
  EXPECT_EQ(cellEdge(-4), 0.25);
  EXPECT_EQ(cellEdge(-5), 0.1875);
  // The status word is a signed i32 in a u32.
  EXPECT_EQ(cellEdge(static_cast<std::int32_t>(std::uint32_t{0xFFFFFFFDu})), 0.375);
}

TEST(Contract, EveryErrorBitHasItsTextAndUnknownBitsAreNamed) {
  for (std::uint32_t b = 0; b < contract::ERR_COUNT; ++b)
    EXPECT_EQ(describeErrors(1u << b), contract::kErrorText[b]);
  EXPECT_EQ(describeErrors(contract::ERR_CAPACITY | contract::ERR_INDEX_RANGE),
            std::string(contract::kErrorText[0]) + ", " + contract::kErrorText[2]);
  EXPECT_NE(describeErrors(1u << contract::ERR_COUNT).find("unknown"), std::string::npos);
}

TEST(Contract, RecordsAreTheirFieldsThenATagWordForEveryLayoutAndWidth) {
  for (LinkFormat f : {LinkFormat::Binary16, LinkFormat::BFloat16, LinkFormat::Binary32, LinkFormat::Binary64}) {
    for (std::uint32_t layout : {contract::LAYOUT_FULL, contract::LAYOUT_DERIVED}) {
      const BufferLayout lay{f, layout};
      const unsigned fields = layout == contract::LAYOUT_FULL ? std::size(contract::kFullFields) : std::size(contract::kDerivedFields);
      EXPECT_EQ(lay.recordBytes(), fields * fieldBytes(f) + contract::TAG_BYTES);
      EXPECT_EQ(lay.recordsPerLine(), contract::LINE_BYTES / lay.recordBytes());
      // A record with a distinct value per field, written and read at every slot.
      link::HostMemory m;
      const auto a = m.allocate(3);
      for (unsigned n = 0; n < 2 * lay.recordsPerLine() + 1; ++n) {
        ContactRecord r;
        double* v[] = {&r.px, &r.py, &r.pz, &r.nx, &r.ny, &r.nz, &r.depth};
        double* dv[] = {&r.d, &r.w};
        for (unsigned k = 0; k < fields; ++k) *(layout == contract::LAYOUT_FULL ? v[k] : dv[k]) = 1.0 + k + n;
        r.pair = 0xABCDEu + n;
        r.flags = static_cast<std::uint8_t>(contract::REC_HIT | (contract::KIND_CONTACT << contract::REC_KIND_SHIFT));
        writeContact(m, a.base, n, lay, false, r);
        const ContactRecord back = readContact(m, a.base, n, lay, false);
        EXPECT_EQ(back.pair, r.pair);
        EXPECT_EQ(back.flags, r.flags);
        const double bv[] = {back.px, back.py, back.pz, back.nx, back.ny, back.nz, back.depth};
        const double bd[] = {back.d, back.w};
        for (unsigned k = 0; k < fields; ++k) EXPECT_EQ(layout == contract::LAYOUT_FULL ? bv[k] : bd[k], 1.0 + k + n);
        // The tag word sits right after the fields: pair in bits 0..23, flags above.
        std::uint32_t tag;
        std::memcpy(&tag, m.line(a.base + n / lay.recordsPerLine()).data() + (n % lay.recordsPerLine()) * lay.recordBytes() +
                              fields * fieldBytes(f), 4);
        EXPECT_EQ(tag & ((1u << contract::TAG_PAIR_BITS) - 1), r.pair);
        EXPECT_EQ(tag >> contract::TAG_FLAGS_SHIFT, r.flags);
      }
    }
  }
}

TEST(Contract, DenseRecordsStartALineAtEveryPairLine) {
  const BufferLayout lay{LinkFormat::Binary32, contract::LAYOUT_DERIVED};  // 5 a line
  ASSERT_EQ(lay.recordsPerLine(), 5u);
  EXPECT_EQ(lay.recordLine(14, true), 2u);
  EXPECT_EQ(lay.recordLine(15, true), 3u);  // the 16th record has a line of its own
  EXPECT_EQ(lay.recordLine(16, true), 4u);
  EXPECT_EQ(lay.recordSlot(16, true), 0u);
  EXPECT_EQ(contactLines(17, lay, true), 5u);
  EXPECT_EQ(contactLines(17, lay, false), 4u);
  const BufferLayout full{LinkFormat::Binary32, contract::LAYOUT_FULL};  // 2 a line: no gaps
  for (std::size_t n = 0; n < 100; ++n) EXPECT_EQ(full.recordLine(n, true), n / 2);
}

TEST(Contract, MaskedRecordsAreTheirFieldsThenTheFlagsByte) {
  for (LinkFormat f : {LinkFormat::Binary16, LinkFormat::Binary32, LinkFormat::Binary64}) {
    for (std::uint32_t layout : {contract::LAYOUT_FULL_MASKED, contract::LAYOUT_DERIVED_MASKED}) {
      const BufferLayout lay{f, layout};
      ASSERT_TRUE(lay.masked());
      const unsigned fields = lay.derived() ? std::size(contract::kDerivedFields) : std::size(contract::kFullFields);
      EXPECT_EQ(lay.recordBytes(), fields * fieldBytes(f) + 1);
      EXPECT_GE(lay.recordBytes() * 8, contract::HEADER_BITS) << "a header must fit a slot";
      link::HostMemory m;
      const auto a = m.allocate(4);
      ContactRecord r;
      r.d = 2.5; r.w = 0.75; r.px = 1; r.depth = 7;
      r.flags = static_cast<std::uint8_t>(contract::REC_HIT | contract::REC_ARITH);
      writeContact(m, a.base, 1, lay, false, r);
      const std::size_t flagsAt = lay.recordSlot(1, false) * lay.recordBytes() + fields * fieldBytes(f);
      EXPECT_EQ(m.line(a.base + lay.recordLine(1, false))[flagsAt], r.flags);
      const ContactRecord back = readContact(m, a.base, 1, lay, false, 42);
      EXPECT_EQ(back.pair, 42u) << "a masked record's pair is the one its position names";
      EXPECT_EQ(back.flags, r.flags);
      EXPECT_EQ(lay.derived() ? back.w : back.depth, lay.derived() ? 0.75 : 7.0);
    }
  }
}

// A compact masked buffer built slot by slot from the header's constants: headers with their
// hits, groups out of pair order (pair lines arrive in any order), a group cut by the end.
TEST(Contract, MaskedBuffersDecodeHeaderByHeader) {
  const BufferLayout lay{LinkFormat::Binary32, contract::LAYOUT_DERIVED_MASKED};  // 9 B, 7 a line
  ASSERT_EQ(lay.recordsPerLine(), 7u);
  link::HostMemory m;
  const auto a = m.allocate(4);
  std::size_t slot = 0;
  auto group = [&](std::uint32_t first, std::uint32_t mask) {
    writeMaskHeader(m, a.base, slot++, lay, {first, mask});
    for (unsigned k = 0; k < contract::HEADER_MASK_BITS; ++k)
      if (mask >> k & 1) {
        ContactRecord r;
        r.d = first + k; r.w = 1;
        r.flags = contract::REC_HIT;
        writeContact(m, a.base, slot++, lay, false, r);
      }
  };
  group(32, 0x8001);  // pairs 32 and 47
  group(0, 0x0006);   // pairs 1 and 2
  group(16, 0x0010);  // pair 20
  const MaskHeader h = readMaskHeader(m, a.base, 0, lay);
  EXPECT_EQ(h.first, 32u);
  EXPECT_EQ(h.mask, 0x8001u);
  auto d = readRecords(m, a.base, slot, lay, false, 48);
  EXPECT_EQ(d.headers, 3u);
  std::vector<std::uint32_t> pairs;
  for (const auto& r : d.records) {
    pairs.push_back(r.pair);
    EXPECT_EQ(r.d, r.pair) << "record and pair must match";
  }
  EXPECT_EQ(pairs, (std::vector<std::uint32_t>{32, 47, 1, 2, 20}));
  // a buffer that ends inside a group (capacity): the records before the end
  d = readRecords(m, a.base, 5, lay, false, 48);
  EXPECT_EQ(d.records.size(), 3u);
  // corrupt headers are errors naming the slot
  EXPECT_THROW(readRecords(m, a.base, slot, lay, false, 40), std::runtime_error);  // pair 47 of 40
  writeMaskHeader(m, a.base, 3, lay, {0, 0});
  try {
    readRecords(m, a.base, slot, lay, false, 48);
    FAIL() << "an empty mask must be refused";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("slot 3"), std::string::npos) << e.what();
  }
  // dense masked: record k is pair k, no headers
  const auto dd = readRecords(m, a.base, 3, lay, true, 3);
  EXPECT_EQ(dd.headers, 0u);
  EXPECT_EQ(dd.records[2].pair, 2u);
}
