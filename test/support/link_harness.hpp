#pragma once
// A scripted requester for link-model tests: issues reads (or writes) of consecutive
// lines whenever allowed, records when each request was accepted and answered.
#include <cstdint>
#include <map>
#include <vector>

#include "link/link_model.hpp"

namespace collide::test {

struct Event {
  std::uint64_t cycle;
  std::uint32_t tag;
  bool operator==(const Event& o) const { return cycle == o.cycle && tag == o.tag; }
};

struct Traffic {
  std::vector<Event> accepted, readResp, writeResp;
  std::map<std::uint32_t, std::uint64_t> acceptCycle;  // tag -> cycle (tags unique here)
};

// Issues `count` reads (writes if `writes`), one per cycle when ready, `burst` at a time:
// after a burst it waits for every response before the next (idle waiting, the case the
// simulator skips). With `skip`, waiting cycles are jumped with nextEventCycle().
inline Traffic runTraffic(link::LinkModel& l, std::uint64_t base, unsigned count, unsigned burst,
                          bool writes, bool skip) {
  Traffic t;
  unsigned issued = 0, done = 0, inBurst = 0;
  while (done < count) {
    const auto in = l.outputs();
    const bool wantIssue = issued < count && inBurst < burst;
    if (skip && !wantIssue && !in.anyEvent()) {
      l.skipTo(l.nextEventCycle());
      continue;
    }
    if (in.rdResp) { t.readResp.push_back({l.cycle(), in.rdResp->tag}); ++done; }
    if (in.wrResp) { t.writeResp.push_back({l.cycle(), in.wrResp->tag}); ++done; }
    link::AfuToLink out;
    if (wantIssue && (writes ? in.wrReqReady : in.rdReqReady)) {
      const std::uint32_t tag = issued;
      if (writes) out.wrReq = link::WriteReq{base + issued % 16, tag, link::Line{}};
      else out.rdReq = link::ReadReq{base + issued % 16, tag};
      t.accepted.push_back({l.cycle(), tag});
      t.acceptCycle[tag] = l.cycle();
      ++issued;
      ++inBurst;
    }
    l.tick(out);
    if (inBurst == burst && done == issued) inBurst = 0;
  }
  return t;
}

}  // namespace collide::test
