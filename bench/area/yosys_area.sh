#!/usr/bin/env bash
# Area proxy for one design: Yosys 0.23 `synth_intel_alm -family cyclonev` (Cyclone V's
# variable-precision DSPs stand in for the paper's Stratix V; bench/README.md says how). Prints one JSON object with
# ALMs (LUT cells), DSP blocks, RAM bits (M10K) and flip-flops, and the LUT cells by their inputs
# (lut6, lut5, lut4; lut3: three or fewer), which say how they can share ALMs.
# usage: bench/area/yosys_area.sh FILE.sv TOP [LOG]
set -euo pipefail
sv="$1"; top="$2"; log="${3:-/dev/null}"
yosys -q -l "$log" -p "read_verilog -sv $sv; synth_intel_alm -family cyclonev -top $top; stat" >/dev/null 2>&1 || {
  echo "yosys failed on $sv (top $top); see $log" >&2; exit 1; }
# synth prints its own statistics before ours: keep only the last block.
awk -v top="$top" '
  /Number of cells:/ { cells = $4; alut = 0; arith = 0; dsp = 0; ff = 0; m10k = 0; l6 = 0; l5 = 0; l4 = 0; l3 = 0 }
  /MISTRAL_ALUT_ARITH/ { arith += $2; next }
  /MISTRAL_ALUT6/ { l6 += $2 }
  /MISTRAL_ALUT5/ { l5 += $2 }
  /MISTRAL_ALUT4/ { l4 += $2 }
  /MISTRAL_ALUT[0-3] / { l3 += $2 }
  /MISTRAL_ALUT[0-9A-Z_]*/ { alut += $2 }
  /MISTRAL_MUL[0-9X]*/ { dsp += $2 }
  /MISTRAL_FF/ { ff += $2 }
  /MISTRAL_M10K/ { m10k += $2 }
  END { printf "{\"top\":\"%s\",\"luts\":%d,\"arith\":%d,\"dsp\":%d,\"ff\":%d,\"m10k\":%d,\"lut6\":%d,\"lut5\":%d,\"lut4\":%d,\"lut3\":%d}\n", top, alut, arith, dsp, ff, m10k, l6, l5, l4, l3 }
' "$log"
