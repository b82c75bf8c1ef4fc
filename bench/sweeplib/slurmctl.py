"""Slurm's commands as the Slurm executor uses them: sbatch, squeue, scancel, sacct, sinfo.
Each raises RuntimeError naming the command and what Slurm said when it fails."""
import shutil
import subprocess

# squeue's states of a job that will still run or is running; any other state is final.
ACTIVE = {"PENDING", "CONFIGURING", "RUNNING", "COMPLETING", "SUSPENDED", "REQUEUED", "REQUEUE_HOLD",
          "REQUEUE_FED", "RESIZING", "SIGNALING", "STAGE_OUT", "STOPPED"}


def _run(cmd, check=True) -> subprocess.CompletedProcess:
    if not shutil.which(cmd[0]):
        raise RuntimeError(f"{cmd[0]} not found: the Slurm executor needs Slurm's client commands on PATH "
                           f"(on a cluster: `module load slurm` or the like; here: tools/setup.sh)")
    r = subprocess.run(cmd, capture_output=True, text=True)
    if check and r.returncode != 0:
        raise RuntimeError(f"{' '.join(cmd)}: {r.stderr.strip() or r.stdout.strip() or f'exit {r.returncode}'}")
    return r


def sbatch(script, args) -> str:
    """Submits; returns the job id."""
    out = _run(["sbatch", "--parsable", *args, str(script)]).stdout.strip()
    return out.split(";")[0]  # --parsable: "id" or "id;cluster"


def queue() -> dict:
    """{"JOBID_INDEX": (state, reason, node)} for this user's jobs (recently ended ones too, for
    as long as slurmctld keeps them: their final state says why a task ended)."""
    r = _run(["squeue", "--me", "-h", "-r", "-t", "all", "-o", "%i|%T|%r|%N"])
    jobs = {}
    for line in r.stdout.splitlines():
        parts = line.split("|")
        if len(parts) == 4:
            jobs[parts[0]] = (parts[1], parts[2], parts[3])
    return jobs


def cancel(job_ids) -> None:
    if job_ids:
        _run(["scancel", *sorted(job_ids)], check=False)  # some may have ended meanwhile


def accounting(job_task: str) -> str:
    """sacct's "STATE exit CODE" for a task that squeue no longer knows, or "" without accounting."""
    r = _run(["sacct", "-n", "-X", "-P", "-j", job_task, "-o", "State,ExitCode"], check=False)
    line = r.stdout.strip().splitlines()[0] if r.returncode == 0 and r.stdout.strip() else ""
    return line.replace("|", " exit ") if line else ""


def nodes(partition=None) -> list:
    """The host names of the partition's nodes (the default partition's without one)."""
    args = ["sinfo", "-h", "-N", "-o", "%N"] + (["-p", partition] if partition else [])
    names = sorted(set(_run(args).stdout.split()))
    if not names:
        raise RuntimeError(f"sinfo: no nodes in {'partition ' + partition if partition else 'the default partition'}")
    return names
