"""A throw-away one-node Slurm cluster for the Slurm executor's tests: its own munged (own key
and socket), slurmctld and slurmd, every file in a temporary directory, on free ports.

Use it as a context manager; it stops its daemons (by their pid) on the way out, also when a
test fails. It needs root: slurmd runs jobs as their submitting user and must be able to
switch to it."""
import os
import shutil
import socket
import subprocess
import tempfile
import time
from pathlib import Path

WHY_ROOT = ("the Slurm executor's tests start a one-node Slurm cluster (munged, slurmctld, slurmd), and "
            "slurmd must run as root to start jobs: run them as root (CI does), after tools/setup.sh")


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _mem_mb() -> int:
    for line in Path("/proc/meminfo").read_text().splitlines():
        if line.startswith("MemTotal:"):
            return int(line.split()[1]) // 1024
    raise RuntimeError("/proc/meminfo: no MemTotal line")


class Cluster:
    def __init__(self):
        self.dir = None
        self.procs = []
        self.env = None

    def __enter__(self):
        if os.geteuid() != 0:
            raise RuntimeError(WHY_ROOT)
        for tool in ("munged", "mungekey", "slurmctld", "slurmd", "sbatch", "squeue"):
            if not shutil.which(tool):
                raise RuntimeError(f"{tool} is not installed: `apt-get install slurm-wlm munge` (tools/setup.sh does "
                                   f"it where no other Slurm's commands are on PATH)")
        self.dir = Path(tempfile.mkdtemp(prefix="collide-slurm-"))
        try:
            self._start()
        except BaseException:
            self.__exit__(None, None, None)
            raise
        return self

    def _start(self):
        d = self.dir
        d.chmod(0o755)  # munged refuses a socket directory others can write to; /tmp is fine (sticky)
        key, sock = d / "munge.key", d / "munge.socket"
        subprocess.run(["mungekey", "--create", f"--keyfile={key}"], check=True, capture_output=True)
        key.chmod(0o400)
        self._daemon(["munged", "--force", f"--key-file={key}", f"--socket={sock}", f"--pid-file={d / 'munged.pid'}",
                      f"--log-file={d / 'munged.log'}", f"--seed-file={d / 'munged.seed'}"], d / "munged.pid")
        host = socket.gethostname().split(".")[0]
        conf = d / "slurm.conf"
        # Memory a little under the machine's, so a job's --mem fits the way it would on a real node.
        conf.write_text(f"""ClusterName=collide-test
SlurmctldHost={host}
SlurmUser=root
SlurmctldPort={free_port()}
SlurmdPort={free_port()}
AuthType=auth/munge
AuthInfo=socket={sock}
CredType=cred/munge
StateSaveLocation={d / 'state'}
SlurmdSpoolDir={d / 'spool'}
SlurmctldPidFile={d / 'slurmctld.pid'}
SlurmdPidFile={d / 'slurmd.pid'}
SlurmctldLogFile={d / 'slurmctld.log'}
SlurmdLogFile={d / 'slurmd.log'}
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
NodeName={host} NodeAddr=127.0.0.1 CPUs={os.cpu_count()} RealMemory={int(_mem_mb() * 0.9)} State=UNKNOWN
PartitionName=test Nodes={host} Default=YES MaxTime=INFINITE State=UP
""")
        (d / "state").mkdir()
        (d / "spool").mkdir()
        self.env = dict(os.environ, SLURM_CONF=str(conf))
        self._daemon(["slurmctld", "-f", str(conf)], d / "slurmctld.pid")
        self._daemon(["slurmd", "-f", str(conf)], d / "slurmd.pid")
        for _ in range(60):  # the node reports in within seconds
            r = subprocess.run(["sinfo", "-h", "-o", "%T"], env=self.env, capture_output=True, text=True)
            if r.returncode == 0 and r.stdout.strip() in ("idle", "mixed", "allocated"):
                return
            time.sleep(0.5)
        raise RuntimeError(f"the test cluster's node never became idle (sinfo: {r.stdout.strip() or r.stderr.strip()}); "
                           f"logs in {d}")

    def _daemon(self, cmd, pid_file: Path):
        r = subprocess.run(cmd, env=self.env or os.environ, capture_output=True, text=True)
        if r.returncode != 0:
            raise RuntimeError(f"{cmd[0]} did not start ({r.returncode}): {r.stderr.strip()}; logs in {self.dir}")
        for _ in range(40):
            if pid_file.exists() and pid_file.read_text().strip():
                self.procs.append(pid_file)
                return
            time.sleep(0.25)
        raise RuntimeError(f"{cmd[0]} wrote no pid file {pid_file}; logs in {self.dir}")

    def __exit__(self, *exc):
        for pid_file in reversed(self.procs):
            try:
                os.kill(int(pid_file.read_text().strip()), 15)
            except (OSError, ValueError):
                pass
        for pid_file in self.procs:  # wait for each to go, so its ports are free again
            try:
                pid = int(pid_file.read_text().strip())
            except (OSError, ValueError):
                continue
            for _ in range(40):
                try:
                    os.kill(pid, 0)
                except OSError:
                    break
                time.sleep(0.25)
        self.procs = []
        if self.dir and not os.environ.get("COLLIDE_KEEP_SLURM"):
            shutil.rmtree(self.dir, ignore_errors=True)
        return False
