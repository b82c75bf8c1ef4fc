#!/usr/bin/env bash
# The local executor, --jobs 1 against --jobs 2, from cold sweep caches: the scpus sweep with its
# Yosys areas, all of it or only some configurations. Before each run it deletes this checkout's
# cached Verilog, host builds, areas, runs and task records of the sweep, and it turns ccache off
# (CCACHE_DISABLE) so that the second run does not compile from the first one's cache. sbt's
# compiled generator stays warm: compile it once before (sbt compile).
# Usage (from a checkout nothing else edits or builds in):
#   bench/results/executors/measure_jobs.sh OUT_DIR [CONFIGS] [JOBS]
# CONFIGS e.g. n1_fp32,n2_fp32 (empty: all); JOBS the --jobs values to run, default "1 2".
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../../.."
out="${1:?usage: measure_jobs.sh OUT_DIR [CONFIGS] [JOBS]}"
configs="${2:-}"
job_counts="${3:-1 2}"
mkdir -p "$out"
export CCACHE_DISABLE=1
for jobs in $job_counts; do
  if [[ -n "$configs" ]]; then
    for c in ${configs//,/ }; do rm -rf "build/sweep/gen/$c" "build/sweep/host/$c"; done
  else
    rm -rf build/sweep/gen build/sweep/host
  fi
  rm -rf build/sweep/area build/sweep/runs/scpus build/sweep/exec/scpus
  start=$(date +%s.%N)
  bench/sweep run scpus ${configs:+--configs "$configs"} --jobs "$jobs" --out "$out/jobs$jobs" \
    > "$out/jobs$jobs.log" 2>&1
  end=$(date +%s.%N)
  cp -r build/sweep/exec/scpus/records "$out/jobs$jobs/records"
  echo "jobs=$jobs wall_s=$(echo "$end - $start" | bc)" | tee -a "$out/times.txt"
done
