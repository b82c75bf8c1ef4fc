#pragma once
// CCI-style channel payloads between the link model and the AFU, on the link's one
// interface clock (200 MHz on HARP v1, 400 MHz on CCI-P platforms; docs/afu-interface.md
// "Link channels"). A std::optional is a valid signal. These are the AFU port's signals;
// the physical channels behind it are the link model's business (LinkParams::channels()).
#include <cstdint>
#include <optional>

#include "link/host_memory.hpp"

namespace collide::link {

struct ReadReq { std::uint64_t addr; std::uint32_t tag; };         // AFU -> host, valid/ready
struct ReadResp { std::uint32_t tag; Line data; };                 // host -> AFU, valid only
struct WriteReq { std::uint64_t addr; std::uint32_t tag; Line data; };  // AFU -> host, valid/ready
struct WriteResp { std::uint32_t tag; };                           // host -> AFU, valid only
struct CsrWrite { std::uint8_t index; std::uint64_t data; };       // host -> AFU, valid only

// What the link drives into the AFU during one cycle.
struct LinkToAfu {
  bool rdReqReady = false;
  bool wrReqReady = false;
  std::optional<ReadResp> rdResp;
  std::optional<WriteResp> wrResp;
  std::optional<CsrWrite> csr;
  // A response or CSR is presented: something an idle AFU must see.
  bool anyEvent() const { return rdResp || wrResp || csr; }
};

// What the AFU drives into the link during one cycle.
struct AfuToLink {
  std::optional<ReadReq> rdReq;
  std::optional<WriteReq> wrReq;
};

}  // namespace collide::link
