#include "driver/afu_driver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace collide::driver {

std::string describeErrors(std::uint32_t f) {
  std::string s;
  for (std::uint32_t b = 0; b < contract::ERR_COUNT; ++b)
    if (f & (1u << b)) s += (s.empty() ? "" : ", ") + std::string(contract::kErrorText[b]);
  if (f >> contract::ERR_COUNT) s += (s.empty() ? "" : ", ") + std::string("unknown flag bits");
  return s.empty() ? "none" : s;
}

void accumulate(StatusLine& into, const StatusLine& s) {
  into.done += s.done;
  into.errors |= s.errors;
  into.pairsProcessed += s.pairsProcessed;
  into.contactsFound += s.contactsFound;
  into.recordsWritten += s.recordsWritten;
  into.nonFinitePairs += s.nonFinitePairs;
  into.flaggedMisses += s.flaggedMisses;
  into.cyclesTotal += s.cyclesTotal;
  into.cyclesLoading += s.cyclesLoading;
  into.cyclesComputing += s.cyclesComputing;
  into.cyclesWaitRead += s.cyclesWaitRead;
  into.cyclesWaitWrite += s.cyclesWaitWrite;
  into.cyclesBroad += s.cyclesBroad;
  into.worldCellLevel = s.worldCellLevel;
  into.worldLarge += s.worldLarge;
}

void accumulate(RunStats& into, const RunStats& r) {
  into.cyclesStepped += r.cyclesStepped;
  into.cyclesSkipped += r.cyclesSkipped;
  into.statusCycle += r.statusCycle;
  into.modelledNs += r.modelledNs;
  into.readLines += r.readLines;
  into.writeLines += r.writeLines;
  into.linkBoundNs += r.linkBoundNs;
}

DriverOptions withManifest(DriverOptions o, const Manifest& m) {
  o.format = m.format;
  o.records = m.records;
  o.arith = m.arith;
  o.maxSpheres = m.maxSpheres;
  o.world = m.world;
  o.runQueue = m.runQueue;
  return o;
}

AfuDriver::AfuDriver(AfuPort& port, const link::LinkParams& link, const DriverOptions& options)
    : port_(port), opt_(options), link_(link, mem_) {
  port_.reset();
}

// run() posts this many CSR writes, one a cycle; the AFU starts on the last (CTRL).
constexpr unsigned kStartCsrWrites = 9;

double linkBoundNs(const link::LinkParams& lp, std::uint64_t readLines, std::uint64_t writeLines) {
  // The model counts latencies in whole cycles (rounded to nearest): so does the bound,
  // or a latency that rounds down would put the bound above the model.
  auto asDrawn = [&](double ns) { return static_cast<double>(lp.nsToCycles(ns)) * lp.cycleNs(); };
  double rdTrip = std::numeric_limits<double>::infinity(), wrTrip = rdTrip;
  for (const auto& c : lp.channels()) {  // the fastest channel sets the shortest trips
    rdTrip = std::min(rdTrip, asDrawn(c.readLatencyMinNs));
    wrTrip = std::min(wrTrip, asDrawn(c.writeLatencyMinNs));
  }
  // Lines move over every channel at once, but the AFU port takes one a cycle at most.
  // n lines are counted as n line times at that rate. The model charges a line's
  // bandwidth as it leaves, so each channel's last line needs none after it: n lines over
  // C channels may finish up to C line times sooner. The CSR writes after the first (the
  // only one counted) absorb that while it is at most kStartCsrWrites - 1 cycles, as on
  // every preset; beyond that the excess is given back, so the bound holds for any
  // channels a scene sets.
  const double channels = static_cast<double>(lp.channels().size());
  const double absorbed = (kStartCsrWrites - 1) * lp.cycleNs();
  auto transferNs = [&](std::uint64_t lines, double aggregateGBps) {
    const double bw = aggregateGBps > 0 ? lp.lineBytes / aggregateGBps : 0.0;  // bytes / (GB/s) = ns
    const double perLine = std::max(bw, lp.cycleNs());
    const double t = static_cast<double>(lines) * perLine - std::max(0.0, channels * perLine - absorbed);
    return std::max(0.0, t);
  };
  const double transfer = std::max(transferNs(readLines, lp.aggregateReadGBps()),
                                   transferNs(writeLines, lp.aggregateWriteGBps()));
  return lp.transactionOverheadNs + asDrawn(lp.csrWriteNs) + lp.pollNs + rdTrip + wrTrip + transfer;
}

double modelledRunNs(const link::LinkParams& lp, std::uint64_t statusCycle) {
  // The done flag lands at the end of the status cycle; the host, polling back to back
  // from the start, sees it at the end of the first poll that begins after that.
  const double commitNs = static_cast<double>(statusCycle) * lp.cycleNs();
  const double seenNs = lp.pollNs > 0 ? (std::ceil(commitNs / lp.pollNs) + 1) * lp.pollNs : commitNs;
  return lp.transactionOverheadNs + seenNs;
}

// Configure, then start (docs/afu-interface.md CSR table): kStartCsrWrites posted writes.
void AfuDriver::postCsrs(const RunCsrs& c) {
  using namespace contract;
  link_.hostWriteCsr(CSR_SPHERE_BASE, c.sphereBase);
  link_.hostWriteCsr(CSR_NUM_SPHERES, c.numSpheres);
  link_.hostWriteCsr(CSR_PAIR_BASE, c.pairBase);
  link_.hostWriteCsr(CSR_NUM_PAIRS, c.numPairs);
  link_.hostWriteCsr(CSR_CONTACT_BASE, c.contactBase);
  link_.hostWriteCsr(CSR_CONTACT_CAPACITY, c.capacity);
  link_.hostWriteCsr(CSR_STATUS_ADDR, c.statusAddr);
  link_.hostWriteCsr(CSR_MODE, c.mode);
  link_.hostWriteCsr(CSR_CTRL, CTRL_START);
}

void AfuDriver::hung(std::uint64_t statusAddr) const {
  std::ostringstream m;
  m << "AFU hung: no status line after " << opt_.watchdogCycles << " cycles (simulated-cycle watchdog); "
    << link_.readsOutstanding() << " reads and " << link_.writesOutstanding()
    << " writes outstanding, " << link_.stats().readResponses << " read and "
    << link_.stats().writeResponses << " write responses delivered, AFU "
    << (port_.idle() ? "idle-waiting" : "busy");
  throw AfuError(m.str(), readStatus(mem_, statusAddr));
}

// One step of AFU and link: while nothing arrives and the AFU idle-waits (skipping on), a
// jump to the link's next event, at most to `limit`; else one clocked cycle. True when that
// cycle delivered a write response, the only thing that changes host memory.
bool AfuDriver::advance(std::uint64_t limit, RunStats& stats) {
  const link::LinkToAfu in = link_.outputs();
  if (opt_.skipIdle && !in.anyEvent() && port_.idle()) {
    const std::uint64_t to = std::min(link_.nextEventCycle(), limit);
    if (to > link_.cycle()) {
      port_.skipIdleCycles(to - link_.cycle());
      stats.cyclesSkipped += to - link_.cycle();
      link_.skipTo(to);
      return false;
    }
  }
  port_.setInputs(in);
  const link::AfuToLink out = port_.evalOutputs();
  port_.clockEdge();
  link_.tick(out);
  ++stats.cyclesStepped;
  return in.wrResp.has_value();
}

// Start one run and clock AFU and link until its status line says done; fills r.stats and
// r.status.
void AfuDriver::execute(const RunCsrs& c, RunResult& r) {
  const std::uint64_t t0 = link_.cycle();
  const std::uint64_t reads0 = link_.stats().readsAccepted, writes0 = link_.stats().writesAccepted;
  using namespace contract;
  postCsrs(c);

  const std::uint64_t deadline = t0 + opt_.watchdogCycles;
  for (;;) {
    if (link_.cycle() >= deadline) hung(c.statusAddr);
    // The status line is the AFU's last write.
    if (advance(deadline, r.stats) && mem_.load<std::uint32_t>(c.statusAddr, STATUS_DONE) != 0) break;
  }

  // Modelled host time: statusCycle counts to the end of the cycle whose write response
  // committed the done flag.
  const auto& lp = link_.params();
  r.stats.statusCycle = link_.cycle() - t0;
  r.stats.modelledNs = modelledRunNs(lp, r.stats.statusCycle);
  r.stats.readLines = link_.stats().readsAccepted - reads0;
  r.stats.writeLines = link_.stats().writesAccepted - writes0;
  r.stats.linkBoundNs = linkBoundNs(lp, r.stats.readLines, r.stats.writeLines);
  r.status = readStatus(mem_, c.statusAddr);
}

RunResult AfuDriver::run(const SphereTable& spheres, const PairList& pairs) {
  const std::size_t n = pairs.size();
  if (spheres.size() > opt_.maxSpheres)
    throw std::invalid_argument("rtl: " + std::to_string(spheres.size()) + " spheres, the AFU holds " +
                                std::to_string(opt_.maxSpheres));
  if (n >= (std::size_t{1} << 24)) throw std::invalid_argument("rtl: NUM_PAIRS must be < 2^24");
  if (link_.readsOutstanding() || link_.writesOutstanding())
    throw std::logic_error("AfuDriver::run: the link still has requests in flight from the last run");

  // Shared buffers. Compact mode can write at most one record per pair (masked: and a
  // header per group with a hit), so the buffer never runs short.
  mem_.releaseAll();
  const BufferLayout lay = layout();
  const std::size_t capacity = opt_.dense ? n : lay.compactSlotsFor(n);
  const auto sph = mem_.allocate(std::max<std::uint64_t>(1, sphereLines(spheres.size(), opt_.format)));
  const auto pl = mem_.allocate(std::max<std::uint64_t>(1, pairLines(n)));
  const auto ct = mem_.allocate(std::max<std::uint64_t>(1, contactLines(capacity, lay, opt_.dense)));
  const auto st = mem_.allocate(1);
  const auto outOfRange = writeSphereTable(mem_, sph.base, spheres, opt_.format);
  writePairList(mem_, pl.base, pairs);

  RunResult r;
  // Scan the pairs only when a sphere did not fit: the usual call pays nothing per pair.
  if (std::find(outOfRange.begin(), outOfRange.end(), std::uint8_t{1}) != outOfRange.end())
    for (std::size_t k = 0; k < n; ++k)
      if ((pairs.i[k] < outOfRange.size() && outOfRange[pairs.i[k]]) || (pairs.j[k] < outOfRange.size() && outOfRange[pairs.j[k]]))
        r.rangePairs.push_back(static_cast<std::uint32_t>(k));
  execute(RunCsrs{sph.base, spheres.size(), pl.base, n, ct.base, capacity, st.base, opt_.dense ? contract::MODE_DENSE : 0u}, r);
  const std::size_t written = std::min<std::size_t>(r.status.recordsWritten, capacity);
  std::size_t headers = 0;
  try {
    auto d = readRecords(mem_, ct.base, written, lay, opt_.dense, n);
    r.records = std::move(d.records);
    headers = d.headers;
  } catch (const std::runtime_error& e) {
    throw AfuError(std::string("AFU run: ") + e.what() + " (" + std::to_string(n) + " pairs sent, " +
                       std::to_string(r.status.pairsProcessed) + " processed, " + std::to_string(r.status.contactsFound) +
                       " contacts, " + std::to_string(r.status.recordsWritten) + " records written, capacity " +
                       std::to_string(capacity) + ")",
                   r.status);
  }
  check(r, n, capacity, headers);
  rebuildDerived(spheres, r, &pairs);
  return r;
}

// Rebuild pos, normal and depth from d, w and the spheres as the link carried them; a
// record's spheres are pair list entries, or (pairs null, world mode) its pair field.
void AfuDriver::rebuildDerived(const SphereTable& spheres, RunResult& r, const PairList* pairs) const {
  if (!layout().derived()) return;
  for (auto& rec : r.records) {
    double s1[4], s2[4], v[7];
    linkSphere(spheres, pairs ? pairs->i[rec.pair] : worldPairI(rec.pair), opt_.format, s1);
    linkSphere(spheres, pairs ? pairs->j[rec.pair] : worldPairJ(rec.pair), opt_.format, s2);
    rebuildContact(opt_.arith, s1, s2, rec.d, rec.w, rec.flags, v);
    rec.px = v[0]; rec.py = v[1]; rec.pz = v[2]; rec.nx = v[3]; rec.ny = v[4]; rec.nz = v[5]; rec.depth = v[6];
  }
}

WorldRunResult AfuDriver::runWorld(const SphereTable& spheres, std::size_t capacityHint) {
  if (!opt_.world)
    throw std::invalid_argument("rtl: this AFU has no world mode (its manifest has no afu.world; generate the world preset)");
  if (spheres.size() > opt_.maxSpheres)
    throw std::invalid_argument("rtl world mode: " + std::to_string(spheres.size()) + " spheres, the AFU holds " +
                                std::to_string(opt_.maxSpheres));
  if (link_.readsOutstanding() || link_.writesOutstanding())
    throw std::logic_error("AfuDriver::runWorld: the link still has requests in flight from the last run");
  const BufferLayout lay = layout();
  std::size_t capacity = capacityHint ? capacityHint : worldCapacity(spheres.size());
  WorldRunResult w;
  RunStats total;
  for (;;) {
    mem_.releaseAll();
    std::vector<std::uint8_t> outOfRange;
    const RunCsrs c = stageWorld(spheres, capacity, outOfRange);
    w.run = RunResult{};
    ++w.attempts;
    execute(c, w.run);
    accumulate(total, w.run.stats);
    const StatusLine& s = w.run.status;
    if ((s.errors & contract::ERR_CAPACITY) && s.contactsFound > capacity && w.attempts == 1) {
      capacity = s.contactsFound;  // every contact counted: room for all of them, once more
      continue;
    }
    const std::size_t written = std::min<std::size_t>(s.recordsWritten, capacity);
    w.run.records = readRecords(mem_, c.contactBase, written, lay, false, 0).records;
    finishWorld(spheres, outOfRange, capacity, w);
    w.run.stats = total;
    return w;
  }
}

std::size_t AfuDriver::worldCapacity(std::size_t spheres) { return std::max<std::size_t>(64, 8 * spheres); }

// A world run's buffers in host memory (after those already allocated): the table written
// in the link format, a contact buffer of `capacity` records, a status line.
RunCsrs AfuDriver::stageWorld(const SphereTable& spheres, std::size_t capacity, std::vector<std::uint8_t>& outOfRange) {
  const auto sph = mem_.allocate(std::max<std::uint64_t>(1, sphereLines(spheres.size(), opt_.format)));
  const auto ct = mem_.allocate(std::max<std::uint64_t>(1, contactLines(capacity, layout(), false)));
  const auto st = mem_.allocate(1);
  outOfRange = writeSphereTable(mem_, sph.base, spheres, opt_.format);
  return RunCsrs{sph.base, spheres.size(), 0, 0, ct.base, capacity, st.base, contract::MODE_WORLD};
}

void AfuDriver::finishWorld(const SphereTable& spheres, const std::vector<std::uint8_t>& outOfRange,
                            std::size_t capacity, WorldRunResult& w) const {
  checkWorld(w.run, spheres.size(), capacity);
  for (std::uint32_t k = 0; k < outOfRange.size(); ++k)
    if (outOfRange[k]) w.rangeSpheres.push_back(k);
  for (auto& rec : w.run.records)
    if (outOfRange[worldPairI(rec.pair)] || outOfRange[worldPairJ(rec.pair)]) rec.flags |= contract::REC_HOST_RANGE;
  rebuildDerived(spheres, w.run, nullptr);
}

// The run queue holds one run behind the current one: run k is posted once the host has
// seen run k - 2's status line (the AFU has then moved run k - 1 up), at the end of the
// poll that sees it. The AFU reads run k's table while run k - 1 computes.
void AfuDriver::executeQueue(const std::vector<RunCsrs>& runs, std::vector<RunResult>& out, RunStats& stats) {
  const auto& lp = link_.params();
  const std::uint64_t t0 = link_.cycle();
  const std::uint64_t reads0 = link_.stats().readsAccepted, writes0 = link_.stats().writesAccepted;
  constexpr std::uint64_t kNever = std::numeric_limits<std::uint64_t>::max();
  const std::size_t n = runs.size();
  out.assign(n, RunResult{});
  std::vector<std::uint64_t> seenAt(n, kNever);  // cycle at which the host has seen run k's status
  std::size_t posted = 0, waiting = 0;           // runs started; the first not yet done
  std::uint64_t progress = t0;                   // the last status seen: the watchdog counts from it
  auto due = [&]() { return posted < 2 ? t0 : seenAt[posted - 2]; };
  for (;;) {
    while (posted < n && link_.cycle() >= due()) postCsrs(runs[posted++]);
    if (link_.cycle() >= progress + opt_.watchdogCycles) hung(runs[waiting].statusAddr);
    std::uint64_t limit = progress + opt_.watchdogCycles;  // a skip stops where the host posts
    if (posted < n) limit = std::min(limit, due());
    if (!advance(limit, stats)) continue;
    while (waiting < n && mem_.load<std::uint32_t>(runs[waiting].statusAddr, contract::STATUS_DONE) != 0) {
      const std::uint64_t c = link_.cycle() - t0;
      out[waiting].stats.statusCycle = c;
      // The host polls back to back from t0: the poll that starts after the commit sees it.
      const double seenNs = lp.pollNs > 0 ? (std::ceil(c * lp.cycleNs() / lp.pollNs) + 1) * lp.pollNs : c * lp.cycleNs();
      seenAt[waiting] = t0 + static_cast<std::uint64_t>(std::ceil(seenNs / lp.cycleNs()));
      progress = link_.cycle();
      ++waiting;
    }
    if (waiting == n) break;
  }
  stats.statusCycle = out.back().stats.statusCycle;
  stats.modelledNs = modelledRunNs(lp, stats.statusCycle);
  stats.readLines = link_.stats().readsAccepted - reads0;
  stats.writeLines = link_.stats().writesAccepted - writes0;
  stats.linkBoundNs = linkBoundNs(lp, stats.readLines, stats.writeLines);
  for (std::size_t k = 0; k < n; ++k) out[k].status = readStatus(mem_, runs[k].statusAddr);
}

WorldBatchResult AfuDriver::runWorlds(const std::vector<SphereTable>& tables) {
  WorldBatchResult b;
  if (!opt_.runQueue || tables.size() < 2) {
    for (const auto& t : tables) {
      b.runs.push_back(runWorld(t));
      accumulate(b.stats, b.runs.back().run.stats);
      ++b.calls;
    }
    return b;
  }
  if (!opt_.world)
    throw std::invalid_argument("rtl: this AFU has no world mode (its manifest has no afu.world; generate the world preset)");
  for (std::size_t k = 0; k < tables.size(); ++k)
    if (tables[k].size() > opt_.maxSpheres)
      throw std::invalid_argument("rtl world mode: table " + std::to_string(k) + " has " + std::to_string(tables[k].size()) +
                                  " spheres, the AFU holds " + std::to_string(opt_.maxSpheres));
  if (link_.readsOutstanding() || link_.writesOutstanding())
    throw std::logic_error("AfuDriver::runWorlds: the link still has requests in flight from the last run");
  const BufferLayout lay = layout();
  mem_.releaseAll();
  std::vector<RunCsrs> csrs;
  std::vector<std::vector<std::uint8_t>> outOfRange;
  for (const auto& t : tables) {
    outOfRange.emplace_back();
    csrs.push_back(stageWorld(t, worldCapacity(t.size()), outOfRange.back()));
  }
  std::vector<RunResult> out;
  executeQueue(csrs, out, b.stats);
  b.calls = 1;
  // Read every run's records before any run again (runWorld reuses host memory).
  std::vector<std::size_t> again;
  b.runs.resize(tables.size());
  for (std::size_t k = 0; k < tables.size(); ++k) {
    WorldRunResult& w = b.runs[k];
    w.run = std::move(out[k]);
    w.attempts = 1;
    const StatusLine& s = w.run.status;
    if ((s.errors & contract::ERR_CAPACITY) && s.contactsFound > csrs[k].capacity) {
      again.push_back(k);
      continue;
    }
    const std::size_t written = std::min<std::size_t>(s.recordsWritten, csrs[k].capacity);
    w.run.records = readRecords(mem_, csrs[k].contactBase, written, lay, false, 0).records;
    finishWorld(tables[k], outOfRange[k], csrs[k].capacity, w);
  }
  for (auto k : again) {
    const StatusLine first = b.runs[k].run.status;
    b.runs[k] = runWorld(tables[k], first.contactsFound);  // room for every contact it counted
    b.runs[k].attempts += 1;
    accumulate(b.stats, b.runs[k].run.stats);
    ++b.calls;
  }
  return b;
}

// A world run's records: hits only, each pair once, i < j within the table, as many as
// the AFU counted; anything else is an AFU bug.
void AfuDriver::checkWorld(const RunResult& r, std::size_t spheres, std::size_t capacity) const {
  const StatusLine& s = r.status;
  auto fail = [&](const std::string& m) { throw AfuError("AFU world run: " + m, s); };
  if (opt_.throwOnErrorFlags && (s.errors & ~std::uint32_t{contract::ERR_NONFINITE}))
    fail("error flags 0x" + [&] { std::ostringstream o; o << std::hex << s.errors; return o.str(); }() + " (" +
         describeErrors(s.errors) + ")");
  if (s.recordsWritten > capacity)
    fail("records written " + std::to_string(s.recordsWritten) + " > capacity " + std::to_string(capacity));
  if (!(s.errors & contract::ERR_CAPACITY) && s.recordsWritten != s.contactsFound)
    fail("contacts found " + std::to_string(s.contactsFound) + " != records written " + std::to_string(s.recordsWritten));
  if (s.pairsProcessed < s.contactsFound)
    fail("candidates " + std::to_string(s.pairsProcessed) + " < contacts " + std::to_string(s.contactsFound));
  std::vector<std::uint32_t> seen;
  seen.reserve(r.records.size());
  for (const auto& c : r.records) {
    const auto i = worldPairI(c.pair), j = worldPairJ(c.pair);
    if (!(i < j && j < spheres))
      fail("record names spheres (" + std::to_string(i) + ", " + std::to_string(j) + ") of " + std::to_string(spheres));
    if (!c.hit()) fail("record for (" + std::to_string(i) + ", " + std::to_string(j) + ") without the hit flag");
    seen.push_back(c.pair);
  }
  std::sort(seen.begin(), seen.end());
  if (std::adjacent_find(seen.begin(), seen.end()) != seen.end()) fail("two records for one pair of spheres");
}

// Every pair sent must be accounted for, and the records must be consistent with the
// counters; anything else is an AFU bug worth stopping for.
void AfuDriver::check(const RunResult& r, std::size_t n, std::size_t capacity, std::size_t headers) const {
  const StatusLine& s = r.status;
  auto fail = [&](const std::string& m) { throw AfuError("AFU run: " + m, s); };
  if (opt_.throwOnErrorFlags && (s.errors & ~std::uint32_t{contract::ERR_NONFINITE}))
    fail("error flags 0x" + [&] { std::ostringstream o; o << std::hex << s.errors; return o.str(); }() +
         " (" + describeErrors(s.errors) + ")" +
         (s.firstBadPair != contract::NO_BAD_PAIR ? ", first bad pair " + std::to_string(s.firstBadPair) : ""));
  if (s.errors & (contract::ERR_TOO_MANY_SPHERES | contract::ERR_BAD_CONFIG)) return;  // nothing computed by contract
  if (s.pairsProcessed != n)
    fail("pairs processed " + std::to_string(s.pairsProcessed) + " != pairs sent " + std::to_string(n));
  if (s.recordsWritten > capacity)
    fail("records written " + std::to_string(s.recordsWritten) + " > capacity " + std::to_string(capacity));
  if (opt_.dense) {
    if (s.recordsWritten != n)
      fail("dense mode: " + std::to_string(s.recordsWritten) + " records for " + std::to_string(n) + " pairs");
    for (std::size_t k = 0; k < r.records.size(); ++k)
      if (r.records[k].pair != k) fail("dense record " + std::to_string(k) + " names pair " + std::to_string(r.records[k].pair));
  } else {
    // Compact: the hits, and the misses the AFU flagged (so that no flag is lost with its miss).
    std::vector<bool> seen(n, false);
    std::size_t flagged = 0;
    for (const auto& c : r.records) {
      if (c.pair >= n) fail("record names pair " + std::to_string(c.pair) + " of " + std::to_string(n));
      if (seen[c.pair]) fail("two records for pair " + std::to_string(c.pair));
      if (c.flaggedMiss()) ++flagged;
      else if (!c.hit()) fail("compact record for pair " + std::to_string(c.pair) + " without the hit flag or an error flag");
      seen[c.pair] = true;
    }
    if (!(s.errors & contract::ERR_CAPACITY)) {
      if (s.recordsWritten != s.contactsFound + s.flaggedMisses + headers)
        fail("contacts found " + std::to_string(s.contactsFound) + " + flagged misses " + std::to_string(s.flaggedMisses) +
             (headers ? " + mask headers " + std::to_string(headers) : "") + " != records written " +
             std::to_string(s.recordsWritten));
      if (flagged != s.flaggedMisses)
        fail(std::to_string(flagged) + " flagged misses among the records, the status line counts " +
             std::to_string(s.flaggedMisses));
    }
  }
}

ContactSet AfuDriver::toContactSet(const RunResult& r, std::size_t n) const {
  ContactSet c;
  c.resize(n);
  c.format = opt_.format;
  for (auto k : r.rangePairs) c.flags[k] |= contract::REC_HOST_RANGE;
  for (const auto& rec : r.records) {
    if (rec.pair >= n) continue;
    const std::size_t k = rec.pair;
    c.flags[k] |= rec.flags;
    if (!rec.hit()) continue;
    c.hit[k] = 1;
    c.px[k] = rec.px; c.py[k] = rec.py; c.pz[k] = rec.pz;
    c.nx[k] = rec.nx; c.ny[k] = rec.ny; c.nz[k] = rec.nz;
    c.depth[k] = rec.depth;
  }
  return c;
}

}  // namespace collide::driver
