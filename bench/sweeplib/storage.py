"""Whether the nodes that run a Slurm sweep can see its checkout and build/: every task reads
the sources and writes its outputs there, and the driver reads them back."""
import subprocess
from pathlib import Path

# Filesystems only the machine that mounts them can see (`stat -f -c %T` names).
LOCAL = {"ext2/ext3", "ext4", "xfs", "btrfs", "tmpfs", "ramfs", "overlayfs", "zfs", "f2fs", "vfat", "msdos",
         "exfat", "jfs", "reiserfs", "squashfs"}


def fs_type(path: Path) -> str:
    r = subprocess.run(["stat", "-f", "-c", "%T", str(path)], capture_output=True, text=True)
    if r.returncode != 0:
        raise RuntimeError(f"stat -f {path}: {r.stderr.strip()}")
    return r.stdout.strip()


def check(paths, nodes, this_host: str) -> None:
    """Raises when a node other than this one would run tasks and a path is on a local filesystem."""
    others = [n for n in nodes if n.split(".")[0] != this_host]
    if not others:
        return  # a one-node cluster on this machine sees what this machine sees
    for p in paths:
        t = fs_type(p)
        if t in LOCAL:
            raise RuntimeError(
                f"{p} is on a local {t} filesystem, so the nodes {', '.join(others[:5])}"
                f"{' ...' if len(others) > 5 else ''} cannot read it: the Slurm executor needs the checkout and "
                f"its build/ on storage every node mounts at the same path (NFS, Lustre, GPFS, BeeGFS, ...). "
                f"Clone the repository there, or pass --storage-is-shared if these nodes do see {p}")
