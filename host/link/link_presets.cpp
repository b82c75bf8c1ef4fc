#include "link/link_presets.hpp"

#include <stdexcept>

namespace collide::link {

// ---- The factories. Every number names its source; where a source gives only an
// aggregate or nothing, the comment says "assumption" and why the value was chosen.
// Per-call costs without a published figure for a platform keep HARP v1's.

// HARP v1: the struct's defaults (sources in link_params.hpp).
LinkParams LinkParams::qpi() { return LinkParams{}; }

LinkParams LinkParams::ideal() {
  LinkParams p;
  p.name = "ideal";
  p.channelName = "ideal";
  p.readLatencyMinNs = p.readLatencyMaxNs = p.cycleNs();
  p.writeLatencyMinNs = p.writeLatencyMaxNs = p.cycleNs();
  p.readGBps = p.writeGBps = 0.0;
  p.reorder = false;
  p.csrWriteNs = p.cycleNs();
  p.pollNs = 0.0;
  p.transactionOverheadNs = 0.0;
  return p;
}

// HARP v2: Broadwell Xeon + Arria 10 GX in one package; CCI-P multiplexes one QPI-class
// link (CCI-P's VL0) and two PCIe Gen3 x8 links (VH0, VH1) behind one AFU port.
LinkParams LinkParams::harp2() {
  LinkParams p;
  p.name = "harp2";
  // CCI-P's interface clock, 400 MHz (Intel CCI-P reference manual; the HARP v2
  // characterisation, IEEE Access 2018, counts its latencies in these cycles).
  p.clockMHz = 400.0;
  // Bandwidth: the HARP v2 characterisation (IEEE Access 2018) gives only the aggregate,
  // over 20 GB/s through the three links. The split is an assumption: each PCIe Gen3 x8
  // link at the rate Intel's PAC loopback self-test measures on the same link class and
  // FPGA family (6.23 GB/s read, 6.26 GB/s write at once; 7.87 GB/s a direction in
  // theory), and the QPI link 8 GB/s each way, the rest of a just-over-20 total
  // (20.46 GB/s read, 20.52 GB/s write).
  // Latency: the characterisation's FPGA cache hit, 25 cycles at 400 MHz (about 62 ns),
  // is the QPI channel's floor; its 150 ns top (a miss served from host memory) is an
  // assumption. The PCIe round trips, 400-600 ns, are an assumption (a non-coherent PCIe
  // read of host memory, several times the coherent link's). Writes: no published
  // figure, assumed like reads as on HARP v1.
  p.setChannels({{"QPI", 8.0, 8.0, 62.0, 150.0, 62.0, 150.0},
                 {"PCIe0", 6.23, 6.26, 400.0, 600.0, 400.0, 600.0},
                 {"PCIe1", 6.23, 6.26, 400.0, 600.0, 400.0, 600.0}});
  // Outstanding: an assumption. CCI-P takes more requests in flight, but the AFU's default
  // 6-bit tags (docs/afu-interface.md) stop at 64, so the link's limit is set there; raise
  // max_reads/max_writes with the AFU's tags. With 64 in flight over these round trips the
  // AFU sustains about 12 GB/s each way, below the 20.5 aggregate: the tags bind first.
  // CCI-P returns responses out of order.
  p.maxReads = p.maxWrites = 64;
  p.reorder = true;
  // No published CSR/poll figures: assumption, qpi's rule on the fastest channel: a CSR
  // write is one traversal (half the mid round trip, (62+150)/4 = 53 ns), a poll that
  // sees the AFU's write pays the longest round trip (150 ns).
  p.csrWriteNs = 53.0;
  p.pollNs = 150.0;
  // No published HARP v2 start+poll figure: HARP v1's 5 us kept (Alves et al., Section V).
  p.transactionOverheadNs = 5000.0;
  return p;
}

// Intel Programmable Acceleration Card with Arria 10 GX: one PCIe Gen3 x8 link.
LinkParams LinkParams::pac() {
  LinkParams p;
  p.name = "pac";
  // The PAC's FPGA Interface Manager gives the AFU CCI-P at 400 MHz, as on HARP v2
  // (Intel CCI-P reference manual).
  p.clockMHz = 400.0;
  // Bandwidth: Intel's FPGA loopback self-test in the PAC user guide (OPAE fpgadiag)
  // shows about 6.23 GB/s read and 6.26 GB/s write at the same time (7.87 GB/s a
  // direction in theory for Gen3 x8). Latency: no published figure; assumption, a PCIe
  // round trip to host memory of 400-600 ns, writes like reads.
  p.setChannels({{"PCIe", 6.23, 6.26, 400.0, 600.0, 400.0, 600.0}});
  p.maxReads = p.maxWrites = 64;  // the AFU's default tag count, as harp2 (assumption)
  p.reorder = true;               // CCI-P: responses out of order
  // Assumption, qpi's rule: CSR half the mid round trip (250 ns), poll the longest (600 ns).
  p.csrWriteNs = 250.0;
  p.pollNs = 600.0;
  // No published PAC start+poll figure: HARP v1's 5 us kept (Alves et al., Section V).
  p.transactionOverheadNs = 5000.0;
  return p;
}

// A CXL-class link on PCIe 5.0 x16 (CXL 1.1 / 2.0).
LinkParams LinkParams::cxl() {
  LinkParams p;
  p.name = "cxl";
  // Assumption: a CCI-P-like 400 MHz interface clock; the AFU port then carries 25.6 GB/s
  // a direction at one line a cycle.
  p.clockMHz = 400.0;
  // Bandwidth: 64 GB/s a direction, the PCIe 5.0 x16 signalling rate (32 GT/s x 16 lanes)
  // that CXL 1.1/2.0 run on (CXL specification); before flit and CRC overhead, so an
  // upper end. Latency: assumption, 300-400 ns load-to-use, writes like reads.
  p.setChannels({{"CXL", 64.0, 64.0, 300.0, 400.0, 300.0, 400.0}});
  // The AFU's default 64 tags (assumption, as harp2). 64 lines in flight over a 300-400 ns
  // round trip sustain about 10-14 GB/s: the tags bind, then the port, never the link.
  // That is what this preset shows; max_reads/max_writes and clock_mhz move the limits.
  p.maxReads = p.maxWrites = 64;
  p.reorder = true;
  // Assumption, qpi's rule: CSR half the mid round trip (175 ns), poll the longest (400 ns).
  p.csrWriteNs = 175.0;
  p.pollNs = 400.0;
  // No published figure for a CXL accelerator call: HARP v1's 5 us kept (Alves et al.).
  p.transactionOverheadNs = 5000.0;
  return p;
}

// ---- The registry: the same presets with a line for the reader and the sources of the
// numbers above, for `collide info --links`. Keep them next to the factories.

const std::vector<LinkPreset>& presets() {
  static const std::vector<LinkPreset> all = {
      {"ideal", {}, "preloaded data: one-cycle trips, only the AFU port's line a cycle, no per-call costs",
       {"not a platform: the paper's 'memory access instantaneous' case (Alves et al., Figure 7)"},
       LinkParams::ideal()},
      {"qpi", {"harp1"}, "HARP v1: Xeon E5-2680 v2 + Stratix V over one QPI link (CCI, SPL2)",
       {"clock 200 MHz: Alves et al., Table II",
        "bandwidth 7 GB/s read, 5 GB/s write: Choi et al., DAC 2016 (measured, sustained)",
        "read latency 200-290 ns: public HARP v1 microbenchmark logs; write latency: assumed equal",
        "64 reads / 64 writes outstanding: SPL2's 6-bit tags",
        "overhead 5 us a call: Alves et al., Section V (start+poll measured about 8.5 us in public "
        "HARP v1 microbenchmark logs)",
        "CSR write 125 ns, poll 290 ns: assumptions (half and all of a QPI round trip)"},
       LinkParams::qpi()},
      {"harp2", {}, "HARP v2: Broadwell Xeon + Arria 10 GX in one package, QPI + 2 x PCIe Gen3 x8 behind CCI-P",
       {"clock 400 MHz: Intel CCI-P reference manual",
        "bandwidth: over 20 GB/s together (HARP v2 characterisation, IEEE Access 2018); the split is an "
        "assumption: PCIe links at the PAC's measured Gen3 x8 rate, QPI 8 GB/s for the rest",
        "QPI latency 62 ns floor: the characterisation's 25-cycle FPGA cache hit at 400 MHz; 150 ns top "
        "assumed",
        "PCIe latency 400-600 ns: assumption; writes assumed like reads",
        "64 reads / 64 writes outstanding: assumption, the AFU's default tags (CCI-P takes more); "
        "they sustain about 12 GB/s over these round trips, below the aggregate",
        "CSR write 53 ns, poll 150 ns: assumptions (qpi's rule on the QPI channel)",
        "overhead 5 us a call: HARP v1's figure kept (none published for HARP v2)"},
       LinkParams::harp2()},
      {"pac", {}, "Intel PAC with Arria 10 GX: one PCIe Gen3 x8 link behind CCI-P",
       {"clock 400 MHz: Intel CCI-P reference manual",
        "bandwidth 6.23 GB/s read, 6.26 GB/s write at once: the FPGA loopback self-test in Intel's PAC "
        "user guide (OPAE); 7.87 GB/s a direction in theory",
        "latency 400-600 ns: assumption (a PCIe round trip); writes assumed like reads",
        "64 reads / 64 writes outstanding: assumption, the AFU's default tags (enough for 6.2 GB/s here)",
        "CSR write 250 ns, poll 600 ns: assumptions (qpi's rule)",
        "overhead 5 us a call: HARP v1's figure kept (none published for the PAC)"},
       LinkParams::pac()},
      {"cxl", {}, "a CXL 1.1/2.0-class link on PCIe 5.0 x16",
       {"clock 400 MHz: assumption (CCI-P-like): the AFU port carries 25.6 GB/s a direction",
        "bandwidth 64 GB/s a direction: PCIe 5.0 x16 signalling rate used by CXL 1.1/2.0 (CXL "
        "specification), before protocol overhead",
        "latency 300-400 ns load-to-use: assumption; writes assumed like reads",
        "64 reads / 64 writes outstanding: assumption, the AFU's default tags; over these round trips "
        "they sustain about 12 GB/s, so the tags bind, then the port, never the link",
        "CSR write 175 ns, poll 400 ns: assumptions (qpi's rule)",
        "overhead 5 us a call: HARP v1's figure kept (none published)"},
       LinkParams::cxl()},
  };
  return all;
}

std::vector<std::string> presetNames() {
  std::vector<std::string> names;
  for (const auto& p : presets()) {
    names.push_back(p.name);
    names.insert(names.end(), p.aliases.begin(), p.aliases.end());
  }
  return names;
}

const LinkPreset* findPreset(const std::string& name) {
  for (const auto& p : presets()) {
    if (p.name == name) return &p;
    for (const auto& a : p.aliases)
      if (a == name) return &p;
  }
  return nullptr;
}

LinkParams presetParams(const std::string& name) {
  if (const LinkPreset* p = findPreset(name)) return p->params;
  std::string known;
  for (const auto& n : presetNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown link preset \"" + name + "\" (known: " + known + ")");
}

}  // namespace collide::link
