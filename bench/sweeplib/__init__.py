"""sweeplib: the design-space sweeps behind `bench/sweep` (bench/README.md).

A package: `tools/pyenv -m sweeplib ...` runs the command line (tools/pyenv puts bench/ on
the module path), and other bench scripts import its parts by name, e.g.
`from sweeplib import area`. The modules, in the order a sweep's data flows:
sweeps (the named sweeps and their configurations), sweep (a sweep's steps as a plan),
generate, build, runs, accuracy, area (the steps), local and slurm (the executors, with
tasks, storage, slurmctl, status and progress), report and plots (tables and figures),
machine, isoarea and paths (shared facts), cli and worker (the entry points).
"""
