#!/usr/bin/env bash
# The local executor, --jobs 1 against --jobs 2, from cold sweep caches (ccache stays warm):
# the scpus sweep's first two configurations with their Yosys areas. Deletes this checkout's
# cached Verilog, builds, areas and runs of those configurations before each run.
# Usage (from the checkout): bench/results/executors/measure_jobs.sh OUT_DIR
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../../.."
out="${1:?usage: measure_jobs.sh OUT_DIR}"
mkdir -p "$out"
for jobs in 1 2; do
  rm -rf build/sweep/gen/n1_fp32 build/sweep/gen/n2_fp32 build/sweep/host/n1_fp32 build/sweep/host/n2_fp32 \
         build/sweep/area build/sweep/runs/scpus build/sweep/exec/scpus
  start=$(date +%s.%N)
  bench/sweep run scpus --configs n1_fp32,n2_fp32 --jobs "$jobs" --out "$out/jobs$jobs" > "$out/jobs$jobs.log" 2>&1
  end=$(date +%s.%N)
  cp -r build/sweep/exec/scpus/records "$out/jobs$jobs/records"
  echo "jobs=$jobs wall_s=$(echo "$end - $start" | bc)" | tee -a "$out/times.txt"
done
