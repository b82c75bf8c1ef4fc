// The SCPU fp32-200 for simulation only: a pipeline of its latency (136) around the C++
// SCPU model (DPI-C), cycle for cycle the RTL's handshake, bit for bit its results.
module ScpuModel_cosim(
  input clock, input reset,
  output in_ready, input in_valid,
  input [31:0] in_bits_x1,
  input [31:0] in_bits_y1,
  input [31:0] in_bits_z1,
  input [31:0] in_bits_r1,
  input [31:0] in_bits_x2,
  input [31:0] in_bits_y2,
  input [31:0] in_bits_z2,
  input [31:0] in_bits_r2,
  input [23:0] in_bits_tag,
  input out_ready, output out_valid,
  output out_bits_hit, output [1:0] out_bits_kind,
  output [31:0] out_bits_px,
  output [31:0] out_bits_py,
  output [31:0] out_bits_pz,
  output [31:0] out_bits_nx,
  output [31:0] out_bits_ny,
  output [31:0] out_bits_nz,
  output [31:0] out_bits_depth,
  output [31:0] out_bits_d,
  output [31:0] out_bits_nw,
  output out_bits_nonFinite, output [4:0] out_bits_flags,
  output [23:0] out_bits_tag);
  import "DPI-C" function void collide_scpu_model(
    input int compute_exp, input int compute_sig, input int link_exp, input int link_sig, input int distance,
    input longint x1, input longint y1, input longint z1, input longint r1, input longint x2, input longint y2, input longint z2, input longint r2,
    output longint px, output longint py, output longint pz, output longint nx, output longint ny, output longint nz, output longint depth, output longint d, output longint nw, output int info);
  // A ring of its latency: every stage advances together (en), so the slot written now is
  // the one whose result leaves now, 136 cycles after it entered; nothing is shifted.
  // valid_q is one vector, cleared whole at reset (Verilator refuses a delayed reset loop
  // over more than 64 slots of an unpacked array).
  reg [135:0] valid_q;
  reg [320:0] data_q [0:135];
  reg [7:0] at;
  wire en = !valid_q[at] || out_ready;
  assign in_ready = en;
  longint r_px, r_py, r_pz, r_nx, r_ny, r_nz, r_depth, r_d, r_nw;
  int info;
  always @(posedge clock) begin
    if (reset) begin
      valid_q <= 136'd0;
      at <= 8'd0;
    end else if (en) begin
      if (in_valid) begin
        collide_scpu_model(8, 24, 8, 24, 0,
          64'(in_bits_x1), 64'(in_bits_y1), 64'(in_bits_z1), 64'(in_bits_r1), 64'(in_bits_x2), 64'(in_bits_y2), 64'(in_bits_z2), 64'(in_bits_r2),
          r_px, r_py, r_pz, r_nx, r_ny, r_nz, r_depth, r_d, r_nw, info);
        data_q[at] <= {info[0], info[2:1], r_px[31:0], r_py[31:0], r_pz[31:0], r_nx[31:0], r_ny[31:0], r_nz[31:0], r_depth[31:0], r_d[31:0], r_nw[31:0], info[3], info[12:8], in_bits_tag};
      end
      valid_q[at] <= in_valid;
      at <= at == 8'd135 ? 8'd0 : at + 8'd1;
    end
  end
  assign out_valid = valid_q[at];
  assign {out_bits_hit, out_bits_kind, out_bits_px, out_bits_py, out_bits_pz, out_bits_nx, out_bits_ny, out_bits_nz, out_bits_depth, out_bits_d, out_bits_nw, out_bits_nonFinite, out_bits_flags, out_bits_tag} = data_q[at];
endmodule
