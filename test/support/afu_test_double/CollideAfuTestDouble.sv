// TEST DOUBLE - NOT THE AFU. A tiny hand-written AFU used only by the host's ctest suite to
// exercise the Verilator build path, the VerilatedAfuPort harness (512-bit data, tags,
// back-pressure, reset, tracing, idle-cycle skipping) and the rtl plumbing before the
// generated AFU exists. It follows docs/afu-interface.md for everything but the physics:
//
//   * CSRs 1..8 as documented; CTRL=1 starts a run on a copy of them.
//   * Checks the configuration (error bits 1 and 4), then reads every sphere-table line
//     (data ignored: counted as loading) and every pair line, up to MAXR reads in flight,
//     with tags from a free-tag pool (responses may come back in any order).
//   * Every pair is answered "separated" (no contact): the double computes no geometry.
//     Feed it only batches in which no pair touches. Out-of-range sphere indices are
//     checked for real (error bit 0, first bad pair), so the u16 lanes of the 512-bit
//     read data are exercised.
//   * Dense mode (MODE bit 0): reads one pair line at a time and writes its records (case 0
//     separated, or case 3 invalid), 2 per line, honouring CONTACT_CAPACITY (error bit 2).
//   * The status line last, after every write response, with the cycle counters.
//
// Idle skipping: `io_idle` is high exactly when, with no response and no CSR presented, the
// double drives no request and changes no state but its cycle counters; an edge with
// `io_skipCycles` = n > 0 (only ever given while idle) counts as n cycles. Built with
// +define+NO_SKIP_PORTS it has neither port (only `io_busy`), like an AFU that cannot tell.
//
// Every CSR index, status offset, error bit and record field comes from the generated
// contract (generated/afu_contract.svh); records are the binary32 full layout.
`include "afu_contract.svh"
module CollideAfuTestDouble #(
  parameter int MAX_SPHERES = 1024,
  parameter int MAXR = 64,  // reads in flight (<= 64: one bit per 6-bit tag)
  parameter int MAXW = 64   // writes in flight
) (
  input  logic         clock,
  input  logic         reset,
  input  logic         io_rdReq_ready,
  output logic         io_rdReq_valid,
  output logic [63:0]  io_rdReq_bits_addr,
  output logic [5:0]   io_rdReq_bits_tag,
  input  logic         io_rdResp_valid,
  input  logic [5:0]   io_rdResp_bits_tag,
  input  logic [511:0] io_rdResp_bits_data,
  input  logic         io_wrReq_ready,
  output logic         io_wrReq_valid,
  output logic [63:0]  io_wrReq_bits_addr,
  output logic [5:0]   io_wrReq_bits_tag,
  output logic [511:0] io_wrReq_bits_data,
  input  logic         io_wrResp_valid,
  input  logic [5:0]   io_wrResp_bits_tag,
  input  logic         io_csr_valid,
  input  logic [7:0]   io_csr_bits_index,
  input  logic [63:0]  io_csr_bits_data,
`ifndef NO_SKIP_PORTS
  output logic         io_idle,
  input  logic [31:0]  io_skipCycles,
`endif
  output logic         io_busy
);
  typedef enum logic [3:0] {
    IDLE, CHECK, LOAD, PAIRS, DREAD, DWAIT, DWRITE, DRAIN, STATUS, SWAIT
  } state_t;
  state_t state;

  // binary32 full records: seven 32-bit fields, then the tag word.
  localparam int REC_BITS = (7 * 4 + AFU_TAG_BYTES) * 8;
  localparam int TAG_BIT  = 7 * 32;
  localparam int NCSR     = AFU_CSR_MODE + 1;

  // CSRs as written, and the run's copy taken at start.
  logic [63:0] csr [1:NCSR-1];
  logic [63:0] sphereBase, numSpheres, pairBase, numPairs, contactBase, capacity, statusAddr;
  logic        dense;

  // Read side: a bit per tag, the line each tag asked for, lines issued / received.
  logic [63:0] rdBusy;
  logic [31:0] rdLineOf [0:63];
  logic [6:0]  rdOut;
  logic [31:0] issued, received, lines;  // lines of the current phase (LOAD or PAIRS)
  // Write side.
  logic [63:0] wrBusy;
  logic [6:0]  wrOut;
  // Dense mode: the pair line being answered and the contact line within it.
  logic [31:0]  curLine;
  logic [511:0] curData;
  logic [3:0]   wIdx;

  // Status counters.
  logic [31:0] errors, processed, written, firstBad;
  logic [31:0] cycTotal, cycLoad, cycCompute, cycWaitRd, cycWaitWr;

  // ---- free tags (lowest free; combinational on state only)
  logic [5:0] rdFree, wrFree;
  always_comb begin
    rdFree = 6'd0;
    for (int t = 63; t >= 0; t--) if (!rdBusy[t]) rdFree = t[5:0];
    wrFree = 6'd0;
    for (int t = 63; t >= 0; t--) if (!wrBusy[t]) wrFree = t[5:0];
  end

  // ---- a pair line's 16 pairs: how many are real, which are out of range
  function automatic logic [4:0] pairsIn(input logic [31:0] line, input logic [63:0] n);
    logic [63:0] first;
    first = {32'd0, line} << 4;
    pairsIn = (n - first >= 64'd16) ? 5'd16 : 5'((n - first));
  endfunction

  logic [31:0] respLine;
  logic [4:0]  respCount;
  logic [15:0] respBad;
  logic [31:0] respFirstBad;
  always_comb begin
    respLine = rdLineOf[io_rdResp_bits_tag];
    respCount = pairsIn(respLine, numPairs);
    respBad = 16'd0;
    respFirstBad = 32'hFFFF_FFFF;
    for (int s = 15; s >= 0; s--) begin
      if (5'(s) < respCount &&
          ({48'd0, io_rdResp_bits_data[32*s +: 16]} >= numSpheres ||
           {48'd0, io_rdResp_bits_data[32*s + 16 +: 16]} >= numSpheres)) begin
        respBad[s] = 1'b1;
        respFirstBad = (respLine << 4) + 32'(s);
      end
    end
  end

  // Dense: records 2*wIdx and 2*wIdx+1 of curLine.
  logic [4:0]  curCount;
  logic [3:0]  curWrites;  // contact lines for this pair line
  logic [511:0] denseData;
  logic [31:0] rec0, rec1;
  always_comb begin
    curCount = pairsIn(curLine, numPairs);
    curWrites = 4'((curCount + 5'd1) >> 1);
    rec0 = (curLine << 4) + {27'd0, wIdx, 1'b0};
    rec1 = rec0 + 32'd1;
    denseData = 512'd0;
    for (int s = 0; s < 16; s++) begin
      if (4'(s >> 1) == wIdx && 5'(s) < curCount && {32'd0, (curLine << 4) + 32'(s)} < capacity) begin
        // the tag word: pair index | flags << TAG_FLAGS_SHIFT (an invalid pair: kind 3)
        denseData[REC_BITS * (s % 2) + TAG_BIT +: 32] = ((curLine << 4) + 32'(s)) |
            (({48'd0, curData[32*s +: 16]} >= numSpheres || {48'd0, curData[32*s + 16 +: 16]} >= numSpheres)
                ? 32'(AFU_KIND_INVALID << (AFU_REC_KIND_SHIFT + AFU_TAG_FLAGS_SHIFT)) : 32'd0);
      end
    end
  end

  // ---- outputs (valid never depends on ready)
  logic rdWant, wrWant;
  always_comb begin
    rdWant = 1'b0;
    if ((state == LOAD || state == PAIRS) && issued < lines && rdOut < 7'(MAXR)) rdWant = 1'b1;
    if (state == DREAD && curLine < lines && rdOut < 7'(MAXR)) rdWant = 1'b1;
    io_rdReq_valid = rdWant;
    io_rdReq_bits_tag = rdFree;
    io_rdReq_bits_addr = (state == LOAD ? sphereBase : pairBase) + {32'd0, state == DREAD ? curLine : issued};

    wrWant = 1'b0;
    io_wrReq_bits_addr = 64'd0;
    io_wrReq_bits_data = 512'd0;
    if (state == DWRITE && wIdx < curWrites && {32'd0, rec0} < capacity && wrOut < 7'(MAXW)) begin
      wrWant = 1'b1;
      io_wrReq_bits_addr = contactBase + {32'd0, rec0 >> 1};
      io_wrReq_bits_data = denseData;
    end
    if (state == STATUS) begin
      wrWant = 1'b1;
      io_wrReq_bits_addr = statusAddr;
      io_wrReq_bits_data[8*AFU_STATUS_DONE +: 32]            = 32'd1;
      io_wrReq_bits_data[8*AFU_STATUS_ERROR_FLAGS +: 32]     = errors;
      io_wrReq_bits_data[8*AFU_STATUS_PAIRS_PROCESSED +: 32] = processed;
      io_wrReq_bits_data[8*AFU_STATUS_RECORDS_WRITTEN +: 32] = written;
      io_wrReq_bits_data[8*AFU_STATUS_FIRST_BAD_PAIR +: 32]  = firstBad;
      io_wrReq_bits_data[8*AFU_STATUS_CYCLES_TOTAL +: 32]    = cycTotal;
      io_wrReq_bits_data[8*AFU_STATUS_CYCLES_LOAD +: 32]     = cycLoad;
      io_wrReq_bits_data[8*AFU_STATUS_CYCLES_COMPUTE +: 32]  = cycCompute;
      io_wrReq_bits_data[8*AFU_STATUS_CYCLES_WAIT_RD +: 32]  = cycWaitRd;
      io_wrReq_bits_data[8*AFU_STATUS_CYCLES_WAIT_WR +: 32]  = cycWaitWr;  // found, non-finite: 0
    end
    io_wrReq_valid = wrWant;
    io_wrReq_bits_tag = wrFree;
    io_busy = state != IDLE;
  end

  // ---- idle: nothing happens without a response or CSR but counting
  /* verilator lint_off UNUSEDSIGNAL */  // idleNow is unused without the skip ports
  logic waitRd, waitWr, idleNow;
  /* verilator lint_on UNUSEDSIGNAL */
  always_comb begin
    waitRd = (state == LOAD || state == PAIRS || state == DWAIT) && !rdWant && rdOut != 7'd0;
    waitWr = (state == DWRITE && wIdx < curWrites && {32'd0, rec0} < capacity && wrOut == 7'(MAXW)) ||
             (state == DRAIN && wrOut != 7'd0);
    idleNow = state == IDLE || state == SWAIT || waitRd || waitWr;
  end
`ifndef NO_SKIP_PORTS
  assign io_idle = idleNow;
  wire [31:0] inc = io_skipCycles != 32'd0 ? io_skipCycles : 32'd1;
`else
  wire [31:0] inc = 32'd1;
`endif

  wire rdFire = io_rdReq_valid && io_rdReq_ready;
  wire wrFire = io_wrReq_valid && io_wrReq_ready;
  wire counting = state != IDLE && state != SWAIT;

  always_ff @(posedge clock) begin
    if (reset) begin
      state <= IDLE;
      for (int k = 1; k < NCSR; k++) csr[k] <= 64'd0;
      rdBusy <= 64'd0; rdOut <= 7'd0; wrBusy <= 64'd0; wrOut <= 7'd0;
      issued <= 32'd0; received <= 32'd0; lines <= 32'd0;
      curLine <= 32'd0; curData <= 512'd0; wIdx <= 4'd0;
      errors <= 32'd0; processed <= 32'd0; written <= 32'd0; firstBad <= AFU_NO_BAD_PAIR;
      cycTotal <= 32'd0; cycLoad <= 32'd0; cycCompute <= 32'd0; cycWaitRd <= 32'd0; cycWaitWr <= 32'd0;
      sphereBase <= 64'd0; numSpheres <= 64'd0; pairBase <= 64'd0; numPairs <= 64'd0;
      contactBase <= 64'd0; capacity <= 64'd0; statusAddr <= 64'd0; dense <= 1'b0;
    end else begin
      // CSRs: take effect at once; CTRL=1 starts when idle.
      if (io_csr_valid && io_csr_bits_index != 8'(AFU_CSR_CTRL) && io_csr_bits_index < 8'(NCSR))
        csr[io_csr_bits_index[3:0]] <= io_csr_bits_data;

      // Counters: every cycle of a run up to the status write; n at once when skipping.
      if (counting) begin
        cycTotal <= cycTotal + inc;
        if (state == LOAD) cycLoad <= cycLoad + inc;
        if (waitRd && !io_rdResp_valid) cycWaitRd <= cycWaitRd + inc;
        if ((wrWant && !io_wrReq_ready) || (waitWr && !io_wrResp_valid)) cycWaitWr <= cycWaitWr + inc;
      end

      // Tag pools.
      if (io_rdResp_valid) rdBusy[io_rdResp_bits_tag] <= 1'b0;
      if (rdFire) begin
        rdBusy[rdFree] <= 1'b1;
        rdLineOf[rdFree] <= state == DREAD ? curLine : issued;
      end
      rdOut <= rdOut + (rdFire ? 7'd1 : 7'd0) - (io_rdResp_valid ? 7'd1 : 7'd0);
      if (io_wrResp_valid) wrBusy[io_wrResp_bits_tag] <= 1'b0;
      if (wrFire) wrBusy[wrFree] <= 1'b1;
      wrOut <= wrOut + (wrFire ? 7'd1 : 7'd0) - (io_wrResp_valid ? 7'd1 : 7'd0);

      // A pair line's response: count and check its pairs.
      if (io_rdResp_valid && (state == PAIRS || state == DWAIT)) begin
        processed <= processed + {27'd0, respCount};
        cycCompute <= cycCompute + 32'd1;
        if (respBad != 16'd0) begin
          errors <= errors | AFU_ERR_INDEX_RANGE;
          if (respFirstBad < firstBad) firstBad <= respFirstBad;
        end
      end

      case (state)
        IDLE: if (io_csr_valid && io_csr_bits_index == 8'(AFU_CSR_CTRL) && io_csr_bits_data == 64'(AFU_CTRL_START)) begin
          sphereBase <= csr[AFU_CSR_SPHERE_BASE]; numSpheres <= csr[AFU_CSR_NUM_SPHERES];
          pairBase <= csr[AFU_CSR_PAIR_BASE]; numPairs <= csr[AFU_CSR_NUM_PAIRS];
          contactBase <= csr[AFU_CSR_CONTACT_BASE]; capacity <= csr[AFU_CSR_CONTACT_CAPACITY];
          statusAddr <= csr[AFU_CSR_STATUS_ADDR]; dense <= (csr[AFU_CSR_MODE] & 64'(AFU_MODE_DENSE)) != 0;
          errors <= 32'd0; processed <= 32'd0; written <= 32'd0; firstBad <= AFU_NO_BAD_PAIR;
          cycTotal <= 32'd0; cycLoad <= 32'd0; cycCompute <= 32'd0; cycWaitRd <= 32'd0; cycWaitWr <= 32'd0;
          state <= CHECK;
        end
        CHECK: begin
          if (numPairs >= 64'h100_0000 || (numPairs != 0 && pairBase == 0) ||
              (numSpheres != 0 && sphereBase == 0) || (capacity != 0 && contactBase == 0) || statusAddr == 0) begin
            errors <= errors | AFU_ERR_BAD_CONFIG;
            state <= statusAddr == 0 ? IDLE : STATUS;
          end else if (numSpheres > 64'(MAX_SPHERES)) begin
            errors <= errors | AFU_ERR_TOO_MANY_SPHERES;
            state <= STATUS;
          end else begin
            state <= LOAD;
            issued <= 32'd0; received <= 32'd0;
            lines <= 32'((numSpheres + 64'd3) >> 2);  // 4 spheres a line (binary32)
          end
        end
        LOAD: begin
          if (io_rdResp_valid) received <= received + 32'd1;
          if (rdFire) issued <= issued + 32'd1;
          if (received == lines && rdOut == 7'd0) begin
            issued <= 32'd0; received <= 32'd0; curLine <= 32'd0;
            lines <= 32'((numPairs + 64'd15) >> 4);
            state <= dense ? DREAD : PAIRS;
          end
        end
        PAIRS: begin
          if (io_rdResp_valid) received <= received + 32'd1;
          if (rdFire) issued <= issued + 32'd1;
          if (received == lines && rdOut == 7'd0) state <= DRAIN;
        end
        DREAD: if (curLine == lines) state <= DRAIN;
               else if (rdFire) state <= DWAIT;
        DWAIT: if (io_rdResp_valid) begin
          curData <= io_rdResp_bits_data;
          wIdx <= 4'd0;
          state <= DWRITE;
        end
        DWRITE: begin
          if (wrFire) begin
            wIdx <= wIdx + 4'd1;
            written <= written + ((64'(rec1) < capacity && 5'(rec1 - (curLine << 4)) < curCount) ? 32'd2 : 32'd1);
          end
          if (wIdx == curWrites || {32'd0, rec0} >= capacity) begin
            if ({32'd0, curLine << 4} + {59'd0, curCount} > capacity) errors <= errors | AFU_ERR_CAPACITY;
            curLine <= curLine + 32'd1;
            state <= DREAD;
          end
        end
        DRAIN: if (wrOut == 7'd0) state <= STATUS;
        STATUS: if (wrFire) state <= SWAIT;
        SWAIT: if (io_wrResp_valid) state <= IDLE;
        default: state <= IDLE;
      endcase
    end
  end
endmodule
