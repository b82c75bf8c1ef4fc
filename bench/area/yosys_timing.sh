#!/usr/bin/env bash
# Timing proxy for one design: Yosys 0.23 `synth_intel_alm -family cyclonev` (the area proxy's
# mapping, without IO or clock buffers: a clock buffer has no timing arcs, so no flip-flop
# would launch a path), then `sta` over the cell delays Yosys ships for Cyclone V and again,
# on the same netlist (`sta` keeps its arrivals on the wires), for Arria V (the specify blocks of its intel_alm cell models). Cell delays only: no
# routing, no clock skew. The black boxes named after LOG (a block's RAMs, or the blocks below
# it) are everted: their outputs become inputs of the design, which start paths at time 0 (a
# block RAM's own clock-to-output is not counted), and their inputs outputs, which end them;
# without that a black box, having no timing arcs, would hide every path from its outputs.
# Block RAM Yosys infers itself has no arcs either. bench/sweeplib/area.py's parse_sta reads
# the two reports from the log.
# usage: bench/area/yosys_timing.sh FILE.sv TOP LOG [BLACK_BOX_MODULE ...]
set -euo pipefail
sv="$1"; top="$2"; log="$3"; shift 3
evert=""
if [ $# -gt 0 ]; then evert="select -module $top$(printf ' t:%s' "$@"); expose -evert; select -clear;"; fi
cells="+/intel_alm/common/alm_sim.v +/intel_alm/common/dff_sim.v +/intel_alm/common/mem_sim.v +/intel_alm/common/dsp_sim.v"
yosys -q -l "$log" -p "read_verilog -sv $sv; synth_intel_alm -family cyclonev -noiopad -noclkbuf -top $top; $evert design -save mapped;
  read_verilog -lib -specify -overwrite -D cyclonev $cells; sta;
  design -load mapped; read_verilog -lib -specify -overwrite -D arriav $cells; sta" >/dev/null 2>&1 || {
  echo "yosys failed on $sv (top $top); see $log" >&2; exit 1; }
