"""Markdown tables per sweep, generated from its CSV (numbers are never typed by hand)."""
import csv
from pathlib import Path

from .plots import PAPER_AFU_NS_PER_COLLISION, PAPER_ODE_NS_PER_COLLISION, f, sel
from . import isoarea

PAPER_TABLE_III = {"dsp": 224, "logic_elements": 200844, "memory_bits": 13600474}


def fmt(v, spec):
    return "" if v is None else format(v, spec)


def table(head, rows):
    out = ["| " + " | ".join(head) + " |", "|" + "|".join("---:" if i else "---" for i in range(len(head))) + "|"]
    out += ["| " + " | ".join(str(c) for c in r) + " |" for r in rows]
    return "\n".join(out) + "\n"


def timing_table(rows):
    head = ["config", "hMax", "link", "pairs", "contacts", "AFU us (modelled)", "ns/collision", "ns/pair",
            "link bound us", "x bound", "compute bound us", "x compute", "ODE ns/collision", "simd ns/collision",
            "rtl wall / ODE"]
    body = []
    for r in rows:
        body.append([r["config"], r["hmax"], r["link"], r["pairs"], r["contacts"], fmt(f(r, "modelled_ns") / 1e3, ".2f"),
                     fmt(f(r, "ns_per_collision"), ".2f"), fmt(f(r, "ns_per_pair"), ".2f"),
                     fmt(f(r, "link_bound_ns") / 1e3, ".2f"), fmt(f(r, "over_link_bound"), ".2f"),
                     fmt(f(r, "compute_bound_ns") / 1e3, ".2f"), fmt(f(r, "over_compute_bound"), ".1f"),
                     fmt(f(r, "ode_ns_per_collision"), ".1f"), fmt(f(r, "simd_ns_per_collision"), ".1f"),
                     fmt(f(r, "rtl_wall_over_ode"), ".0f")])
    return table(head, body)


def split_table(rows):
    head = ["config", "hMax", "link", "loading", "computing", "wait reads", "wait writes", "other AFU", "per-call overhead",
            "lines read", "lines written"]
    body = []
    for r in rows:
        tot = f(r, "modelled_ns")
        pc = lambda k: f"{100 * f(r, k) / tot:.0f} %" if tot else ""
        body.append([r["config"], r["hmax"], r["link"], pc("loading_ns"), pc("computing_ns"), pc("wait_read_ns"),
                     pc("wait_write_ns"), pc("other_ns"), pc("overhead_ns"), r["read_lines"], r["write_lines"]])
    return table(head, body)


def area_table(rows):
    head = ["config", "SCPUs", "LUTs (PUC + N x SCPU)", "arith cells", "DSP", "FF", "M10K", "RAM bits (manifest)",
            "one SCPU: LUTs / arith / DSP / FF", "PUC: LUTs / FF / M10K"]
    body, seen = [], set()
    for r in rows:
        if r["config"] in seen or f(r, "scpu_luts") is None:
            continue
        seen.add(r["config"])
        has_puc = f(r, "area_luts") is not None
        total = [r["area_luts"], r["area_arith"], r["area_dsp"], r["area_ff"], r["area_m10k"]] if has_puc else \
            [f"{r['scpus_luts']} (SCPUs only)", r["scpus_arith"], r["scpus_dsp"], r["scpus_ff"], "-"]
        body.append([r["config"], r["scpus"], *total, r["ram_bits"],
                     f"{r['scpu_luts']} / {r['scpu_arith']} / {r['scpu_dsp']} / {r['scpu_ff']}",
                     f"{r['puc_luts']} / {r['puc_ff']} / {r['puc_m10k']}" if has_puc else "not synthesized"])
    return table(head, body) if body else "(area not measured in this run: `--no-area`)\n"


def accuracy_table(rows):
    head = ["SCPU spec", "latency", "pos rel err worst / mean", "normal ulps worst / mean", "depth / ulp(r1+r2) worst / mean",
            "grazing decisions != double", "wide-range decisions != exact (outside band)",
            f"drift from ODE (max / mean, m)", "ns/collision qpi / ideal", "16 SCPUs: LUTs", "DSP"]
    body = []
    ideal = {}
    for r in sel(rows, link="ideal"):
        ideal.setdefault(r["config"], r)
    seen = set()
    for r in sel(rows, link="qpi"):
        if r["config"] in seen:  # one row a configuration (its first scene)
            continue
        seen.add(r["config"])
        i = ideal.get(r["config"], {})
        body.append([r["scpu_spec"] + (f" ({r['records']})" if r.get("records") else ""), r["latency"],
                     f"{fmt(f(r, 'acc_pos_rel_worst'), '.1e')} / {fmt(f(r, 'acc_pos_rel_mean'), '.1e')}",
                     f"{fmt(f(r, 'acc_normal_ulps_worst'), '.2f')} / {fmt(f(r, 'acc_normal_ulps_mean'), '.2f')}",
                     f"{fmt(f(r, 'acc_depth_rs_ulps_worst'), '.2f')} / {fmt(f(r, 'acc_depth_rs_ulps_mean'), '.2f')}",
                     f"{r.get('acc_decision_mismatch_grazing', '')} of {r.get('acc_grazing_pairs', '')}",
                     r.get("acc_wide_mismatch_outside", ""),
                     f"{fmt(f(r, 'drift_max_m'), '.1e')} / {fmt(f(r, 'drift_mean_m'), '.1e')}",
                     f"{fmt(f(r, 'ns_per_collision'), '.2f')} / {fmt(f(i, 'ns_per_collision') if i else None, '.2f')}",
                     r.get("scpus_luts", ""), r.get("scpus_dsp", "")])
    return table(head, body)


def clock_table(rows):
    """Per configuration: the timing proxy's slowest paths (the SCPU, the AFU's other blocks),
    the clock they allow, and the modelled time on each link at the preset's clock and at that
    one (rows of link "<preset>@cells")."""
    cfgs = [r for r in dict((r["config"], r) for r in rows).values() if f(r, "cells_mhz")]
    presets = [p for p in dict.fromkeys(r["link"] for r in rows) if not p.endswith("@cells")]
    by = {(r["config"], r["link"]): r for r in rows}
    ns = lambda r, k: fmt(f(r, k) / 1e3, ".1f") if f(r, k) else ""
    head = ["config", "SCPU latency", "SCPU: ns Cyclone V (Arria V)", "SCPU's slowest path",
            "other blocks: slowest", "ns Cyclone V (Arria V)", "AFU clock the cells allow (MHz)"]
    head += [f"{p}: us at {fmt(f(by.get((cfgs[0]['config'], p), {}), 'clock_mhz'), '.0f')} MHz / at the cells' clock (x)"
             for p in presets] if cfgs else []
    body = []
    for r in cfgs:
        cells = []
        for p in presets:
            a, b = by.get((r["config"], p), {}), by.get((r["config"], p + "@cells"), {})
            ratio = f(b, "modelled_ns") / f(a, "modelled_ns") if f(a, "modelled_ns") and f(b, "modelled_ns") else None
            cells.append(f"{fmt(f(a, 'modelled_ns') and f(a, 'modelled_ns') / 1e3, '.2f')} / "
                         f"{fmt(f(b, 'modelled_ns') and f(b, 'modelled_ns') / 1e3, '.2f')} ({fmt(ratio, '.1f')})")
        body.append([r["config"], r["latency"], f"{ns(r, 'scpu_cyclonev_ps')} ({ns(r, 'scpu_arriav_ps')})", r["scpu_path"],
                     r["rest_block"], f"{ns(r, 'rest_cyclonev_ps')} ({ns(r, 'rest_arriav_ps')})",
                     fmt(f(r, "cells_mhz"), ".1f"), *cells])
    return table(head, body) if body else "(timing not measured in this run: `--no-area`)\n"


def links_table(rows):
    """ns per collision for every configuration (rows) on every link preset (columns), and how
    close each is to its link bound."""
    presets = list(dict.fromkeys(r["link"] for r in rows))
    head = ["format", "link format", "records", "B a record", "hMax"] + [f"{p}: ns/collision (x bound)" for p in presets]
    body = []
    for (cfg, hmax) in dict.fromkeys((r["config"], r["hmax"]) for r in rows):
        rs = {r["link"]: r for r in rows if r["config"] == cfg and r["hmax"] == hmax}
        r0 = next(iter(rs.values()))
        cells = [f"{fmt(f(rs[p], 'ns_per_collision'), '.2f')} ({fmt(f(rs[p], 'over_link_bound'), '.2f')})" if p in rs else ""
                 for p in presets]
        body.append([r0["format"], r0["link_format"], r0["records"], r0["record_bytes"], hmax] + cells)
    return table(head, body)


def isoarea_table(rows, results: Path):
    """Per arithmetic: the SCPUs that fit the chip under each calibration and the time per
    collision at that count on every link (isoarea.py; 16+ SCPUs run in the 16-SCPU time)."""
    import csv
    from . import isoarea
    from .sweeps import ISOAREA_SPECS, built_count
    load = lambda n: list(csv.DictReader(open(results / n / f"{n}.csv", newline="")))
    arith, pucs = load("arith"), load("scpus")
    fit, areas = isoarea.fits(arith, pucs), isoarea.scpu_areas(arith)
    presets = list(dict.fromkeys(r["link"] for r in rows))
    by = {(r["scpu_spec"], int(r["scpus"]), r["link"]): r for r in rows}
    head = ["arithmetic", "one SCPU: ALMs packed / unpacked", "DSPs", "SCPUs that fit: packed / unpacked (limit)",
            "built"] + [f"{p}: ns/collision packed / unpacked" for p in presets]
    body = []
    for spec in ISOAREA_SPECS:
        if spec not in areas:
            continue
        a = areas[spec]
        (np, wp), (nu, wu) = fit[(spec, "packed")], fit[(spec, "unpacked")]
        cell = lambda n, p: fmt(f(by.get((spec, built_count(n), p), {}), "ns_per_collision"), ".2f")
        body.append([spec, f"{int(isoarea.alms(a['luts'], a['arith'], a['ff'], 'packed')):,} / "
                           f"{int(isoarea.alms(a['luts'], a['arith'], a['ff'], 'unpacked')):,}", int(a["dsp"]),
                     f"{np} / {nu} ({wp}, {wu})", f"{built_count(np)} / {built_count(nu)}"] +
                    [f"{cell(np, p)} / {cell(nu, p)}" for p in presets])
    return table(head, body)


def paper_side_by_side(rows):
    """The paper's stated figures next to ours, computed from the sweep's rows."""
    q = sorted((r for r in sel(rows, link="qpi") if f(r, "contacts")), key=lambda r: int(r["hmax"]))
    i = {r["hmax"]: r for r in sel(rows, link="ideal")}
    if not q:
        return ""
    big = q[-1]
    tot = lambda rs, k: sum(f(r, k) for r in rs)
    avg_afu = tot(q, "modelled_ns") / tot(q, "contacts")
    avg_ode = tot(q, "ode_ns") / tot(q, "contacts")
    faster = lambda r: f(r, "modelled_ns") < f(r, "ode_ns")
    k0 = next((k for k, r in enumerate(q) if faster(r)), None)  # the first set the AFU wins ...
    first = q[k0] if k0 is not None and all(faster(r) for r in q[k0:]) else None  # ... and every larger one
    mem = sum(f(big, k) for k in ("loading_ns", "wait_read_ns", "wait_write_ns"))
    bi = i.get(big["hmax"])
    body = [
        ["collisions at the largest set", "4,812 (hMax 10)", f"{int(big['contacts']):,} (hMax {big['hmax']}, {int(big['pairs']):,} pairs tested)"],
        ["AFU ns per collision", f"{PAPER_AFU_NS_PER_COLLISION:.0f} (average)",
         f"{avg_afu:.2f} (all sets: total time / total collisions); {f(big, 'ns_per_collision'):.2f} at hMax {big['hmax']}"],
        ["ODE ns per collision (CPU)", f"{PAPER_ODE_NS_PER_COLLISION:.0f} (average, Xeon E5-2680 v2)",
         f"{avg_ode:.1f} (all sets); {f(big, 'ode_ns_per_collision'):.1f} at hMax {big['hmax']} (this machine, fastest of {big['cpu_repeat']})"],
        ["AFU faster than ODE from", "about 1,000 collisions",
         f"{int(first['contacts']):,} collisions (hMax {first['hmax']})" if first else "not in these sets"],
        ["speedup over ODE at the largest set", "14.81 %",
         f"{f(big, 'ode_ns') / f(big, 'modelled_ns'):.1f}x (simd batch: {f(big, 'ode_ns') / f(big, 'simd_ns'):.1f}x)"],
        ["memory share of the AFU's time (Fig. 6)", "about 48 %",
         f"{100 * mem / f(big, 'modelled_ns'):.0f} % loading + waiting on reads/writes (they overlap a little), "
         f"{100 * f(big, 'overhead_ns') / f(big, 'modelled_ns'):.0f} % per-call overhead, "
         f"{100 * f(big, 'computing_ns') / f(big, 'modelled_ns'):.0f} % computing"],
        ["speedup with memory time ignored (Fig. 7)", "43 % at 4,812 collisions",
         f"{f(big, 'ode_ns') / f(bi, 'modelled_ns'):.1f}x at hMax {big['hmax']} (ideal link)" if bi else ""],
    ]
    return table(["", "paper (HARP v1 hardware)", "ours (Verilated RTL + HARP v1 link model)"], body)


def banked_table(rows):
    """Each replicated configuration beside its banked twin (same SCPUs, scene and link)."""
    twin = {(r["scpus"], r["scene"], r["link"], r.get("ram_ports") or "replicated"): r for r in rows}
    head = ["SCPUs", "hMax", "link", "pairs", "AFU us: copies / banked", "banked / copies", "computing us: copies / banked",
            "sphere table bits: copies / banked", "M20K (est.): copies / banked", "PUC LUTs: copies / banked"]
    body = []
    for (n, scene, link, ram), rep in twin.items():
        bank = twin.get((n, scene, link, "banked"))
        if ram != "replicated" or bank is None:
            continue
        two = lambda k, spec="": f"{fmt(f(rep, k), spec)} / {fmt(f(bank, k), spec)}"
        us = lambda r, k: fmt(f(r, k) / 1e3, ".2f")
        body.append([n, rep["hmax"], link, rep["pairs"], f"{us(rep, 'modelled_ns')} / {us(bank, 'modelled_ns')}",
                     fmt(f(bank, "modelled_ns") / f(rep, "modelled_ns"), ".3f"),
                     f"{us(rep, 'computing_ns')} / {us(bank, 'computing_ns')}",
                     two("sphere_table_bits", ".0f"), two("sphere_table_m20k", ".0f"),
                     two("puc_luts", ".0f") if f(rep, "puc_luts") is not None else "not synthesized"])
    return table(head, body)


def ram_table(ram):
    """SphereRamReport's rows: per table size and SCPU count, bits and M20K blocks of both options."""
    by = {(r["max_spheres"], r["scpus"], r["ram_ports"]): r for r in ram}
    head = ["spheres", "SCPUs", "copies: Mbit", "copies: M20K (% of 5SGXEA7)", "banked: banks", "banked: Mbit",
            "banked: M20K (% of 5SGXEA7)"]
    body = []
    for (size, n, ports), rep in by.items():
        bank = by.get((size, n, "banked"))
        if ports != "replicated" or bank is None:
            continue
        cell = lambda r: f"{r['m20k']} ({r['m20k_pct_5sgxea7']} %)" + ("" if r["fits"] == "true" else ", does not fit")
        body.append([size, n, f"{int(rep['sphere_table_bits']) / 2**20:.2f}", cell(rep), bank["banks"],
                     f"{int(bank['sphere_table_bits']) / 2**20:.2f}", cell(bank)])
    return table(head, body)


def write(name, rows, out: Path) -> Path:
    parts = [f"# Sweep `{name}`\n", "Generated by `bench/sweep` from "
             f"[{name}.csv]({name}.csv); how and where: [MACHINE.md](MACHINE.md).\n"]
    parts += ["## Time\n", timing_table(rows), "\n## Where the time goes (share of the modelled time)\n", split_table(rows)]
    parts += ["\n## Area (Yosys `synth_intel_alm -family cyclonev`)\n", area_table(rows)]
    if any("cells_mhz" in r for r in rows):
        parts += ["\n## Clock (a timing proxy: Yosys `sta` over Cyclone V and Arria V cell delays, no routing)\n",
                  "The slowest path of the SCPU and of the AFU's other blocks, each block timed on its own "
                  "(bench/area/afu_timing.py's cut), and each link run again at the clock the slower one allows "
                  "(link `<preset>@cells`): cell delays only, so that clock is an upper bound of what these builds "
                  "reach, and the time at it a lower bound. bench/README.md, \"Timing proxy\", says what the proxy "
                  "is and is not.\n\n", clock_table(rows)]
    if name == "paper":
        parts += ["\n## Side by side with the paper\n", paper_side_by_side(rows)]
        parts.append(f"\nThe paper (Table III, Stratix V): {PAPER_TABLE_III['logic_elements']:,} logic elements, "
                     f"{PAPER_TABLE_III['dsp']} DSP blocks, {PAPER_TABLE_III['memory_bits']:,} memory bits; "
                     f"{PAPER_AFU_NS_PER_COLLISION:.0f} ns/collision (AFU) and {PAPER_ODE_NS_PER_COLLISION:.0f} "
                     "ns/collision (ODE) on average.\n")
    if name == "isoarea":
        parts += [f"\n## At a fixed chip ({isoarea.CHIP['name']}; calibration in sweeplib/isoarea.py)\n",
                  isoarea_table(rows, out.parent)]
    if name in ("links", "masked"):
        parts += ["\n## ns per collision on every link (modelled; in brackets: modelled / the link model's bound)\n",
                  links_table(rows)]
    if name == "banked":
        parts += ["\n## A copy of the sphere table per SCPU against one banked copy\n", banked_table(rows)]
        if (out / "ram.csv").exists():
            parts += ["\n## Sphere-table RAM against SCPU count (fp32; [ram.csv](ram.csv), from "
                      "`tools/sbt \"Test/runMain collide.afu.SphereRamReport --out bench/results/banked/ram.csv\"`)\n",
                      ram_table(list(csv.DictReader(open(out / "ram.csv", newline=""))))]
    if any(k.startswith("acc_") for k in rows[0]):
        parts += ["\n## What accuracy costs\n", accuracy_table(rows)]
    path = out / f"{name}.md"
    path.write_text("\n".join(parts))
    return path
