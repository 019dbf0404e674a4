#!/usr/bin/env python3
"""Paired, interleaved timing of two strandbench builds on the same render cases.

On a shared, noisy machine two sweeps run minutes apart drift by more than the
effects being judged (compare-runs then flags noise). This runs each case on
both binaries back to back, alternating which goes first, and prints the
median new/old ratio of the frame median and of each pass, with quartiles.

  scripts/paired-compare.py OLD_BINARY NEW_BINARY [--rounds N] [--case 'NAME=render args'] ...
  scripts/paired-compare.py OLD_BINARY NEW_BINARY --suite suites/quick.json [--rounds N]

Without --case or --suite, a fixed set of cases from the quick suite is used.
With --suite, each round sweeps the whole suite with both binaries (alternating
which goes first) and each case's frame median is paired within the round; a
case is SLOWER when its median ratio exceeds 1 + threshold and a one-sided exact
Wilcoxon signed-rank test of the log ratios over rounds gives p < alpha after Holm's
correction over the cases (as compare-runs does by default). Two
sweeps of one binary a minute apart differ by up to 2x per case here, so only
pairs taken within a round are compared (compare-runs on two sweeps judges the
drift, not the build). --keep DIR keeps the sweeps (DIR/roundR-old, -new) and
runs `strandbench compare-runs` on them as paired rounds (--pair), the same test
in the CLI, and prints its table.
"""
import argparse, itertools, json, math, os, shlex, statistics, subprocess, sys, tempfile

DEFAULT_CASES = {
    "osm16-gl": "--scene straight:strands=1000,points=16,head=0 --shadow osm:maps=16 --backend gl",
    "osm16-vk": "--scene straight:strands=1000,points=16,head=0 --shadow osm:maps=16 --backend vulkan",
    "dom3-gl": "--scene straight:strands=1000,points=16,head=0 --shadow dom:layers=3 --backend gl",
    "occupancy-vk": "--scene straight:strands=1000,points=16,head=0 --shadow occupancy --backend vulkan",
    "wavg-vk": "--scene clustered:strands=300,points=12,head=0,alpha=0.3 --shadow dom:layers=3 --oit wavg --backend vulkan",
    "occupancy-oit-gl": "--scene straight:strands=1000,points=16,head=0,alpha=0.5 --shadow occupancy --oit occupancy --backend gl",
    "occupancy-oit-vk": "--scene clustered:strands=300,points=12,head=0,alpha=0.3 --shadow dom:layers=3 --oit occupancy --backend vulkan",
    "peel-gl": "--scene clustered:strands=300,points=12,head=0,alpha=0.3 --shadow dom:layers=3 --oit peel --backend gl",
}
COMMON = "--size 128x128 --repeat 8 --warmup 2 --out /tmp/paired-compare.png --json"


def render(binary, args):
    out = subprocess.run([binary, "render"] + shlex.split(args) + shlex.split(COMMON),
                         capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"{binary} render {args}: exit {out.returncode}\n{out.stderr}")
    d = json.loads(out.stdout)
    return d["frame_ms"]["median"], {p["name"]: p["ms"]["median"] for p in d["passes"]}


# Two-sided 95% quantiles of Student's t for 1..30 degrees of freedom (beyond: 1.96 + 2.4/df).
T975 = [12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228, 2.201, 2.179,
        2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080, 2.074, 2.069, 2.064,
        2.060, 2.056, 2.052, 2.048, 2.045, 2.042]


def t975(df):
    return T975[df - 1] if df <= len(T975) else 1.96 + 2.4 / df


def mean_interval(values):
    """Mean and its 95% t-interval over rounds (None, None for the bounds with one value)."""
    m = statistics.fmean(values)
    if len(values) < 2:
        return m, None, None
    h = t975(len(values) - 1) * statistics.stdev(values) / math.sqrt(len(values))
    return m, m - h, m + h


def ratio_interval(ratios):
    """Geometric mean of paired ratios (one per interleaved round) and its 95% t-interval,
    taken on the log ratios: a ratio and its inverse get mirrored intervals."""
    m, lo, hi = mean_interval([math.log(r) for r in ratios])
    return math.exp(m), (math.exp(lo) if lo is not None else None), (math.exp(hi) if hi is not None else None)


def signed_rank_p(logs):
    """One-sided exact Wilcoxon signed-rank p-value for 'logs are > 0'."""
    d = [x for x in logs if x != 0.0]
    if not d:
        return 1.0
    order = sorted(range(len(d)), key=lambda i: abs(d[i]))
    ranks = [0.0] * len(d)
    i = 0
    while i < len(order):  # average ranks over ties
        j = i
        while j + 1 < len(order) and abs(d[order[j + 1]]) == abs(d[order[i]]):
            j += 1
        for k in range(i, j + 1):
            ranks[order[k]] = (i + j) / 2 + 1
        i = j + 1
    w = sum(r for r, x in zip(ranks, d) if x > 0)
    hits = sum(1 for signs in itertools.product((0, 1), repeat=len(d))
               if sum(r for r, s in zip(ranks, signs) if s) >= w - 1e-9)
    return hits / 2 ** len(d)


def sweep(binary, suite, out):
    res = subprocess.run([binary, "sweep", suite, "--out", out], capture_output=True, text=True)
    if res.returncode != 0:
        sys.exit(f"{binary} sweep {suite}: exit {res.returncode}\n{res.stderr}")
    with open(os.path.join(out, "results.json")) as f:
        return {r["case"]["id"]: r["frame_ms"]["median"] for r in json.load(f)["results"]}



def compare_suite(a):
    ratios = {}
    with tempfile.TemporaryDirectory() as scratch:
        tmp = a.keep or scratch
        folders = {a.old: [], a.new: []}
        for r in range(a.rounds):
            first, second = (a.old, a.new) if r % 2 == 0 else (a.new, a.old)
            got = {}
            for b in (first, second):
                d = os.path.join(tmp, f"round{r}-{'old' if b == a.old else 'new'}")
                got[b] = sweep(b, a.suite, d)
                folders[b].append(d)
            for case, old_ms in got[a.old].items():
                if case in got[a.new] and old_ms > 0:
                    ratios.setdefault(case, []).append(got[a.new][case] / old_ms)
        if a.keep:
            cmd = [a.new, "compare-runs", folders[a.old][0], folders[a.new][0]]
            for o, n in zip(folders[a.old][1:], folders[a.new][1:]):
                cmd += ["--pair", o, n]
            subprocess.run(cmd + ["--threshold", str(a.threshold), "--alpha", str(a.alpha)])
    # Holm's step-down correction over the cases, as compare-runs does by default: with dozens
    # of unchanged cases at alpha each, a few would be SLOWER by chance in every comparison.
    pvals = {case: signed_rank_p([math.log(x) for x in v]) for case, v in ratios.items()}
    adjusted, running = {}, 0.0
    for i, case in enumerate(sorted(pvals, key=pvals.get)):
        running = max(running, min(1.0, (len(pvals) - i) * pvals[case]))
        adjusted[case] = running
    slower = 0
    for case, v in ratios.items():
        med = statistics.median(v)
        q = statistics.quantiles(v, n=4) if len(v) >= 2 else [med, med, med]
        p = pvals[case]
        verdict = "SLOWER" if med > 1 + a.threshold / 100 and adjusted[case] < a.alpha else "ok"
        slower += verdict == "SLOWER"
        print(f"{case:52s} new/old {med:.3f} (quartiles {q[0]:.3f}..{q[2]:.3f}) "
              f"p(slower) {p:.3f} Holm {adjusted[case]:.3f}  {verdict}", flush=True)
    print(f"{len(ratios)} cases, {slower} slower ({a.rounds} rounds, threshold "
          f"{a.threshold}%, alpha {a.alpha}, Holm-corrected over the cases)")
    return 1 if slower else 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("old")
    ap.add_argument("new")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--case", action="append", default=[], help="NAME=render arguments")
    ap.add_argument("--suite", help="pair whole sweeps of this suite, round by round")
    ap.add_argument("--threshold", type=float, default=5.0, help="percent (with --suite)")
    ap.add_argument("--alpha", type=float, default=0.05, help="significance (with --suite)")
    ap.add_argument("--keep", help="with --suite: keep the sweeps here and judge them with compare-runs --pair")
    a = ap.parse_args()
    if a.rounds < 2:
        sys.exit("--rounds: at least 2")
    if a.suite:
        sys.exit(compare_suite(a))
    cases = dict(c.split("=", 1) for c in a.case) if a.case else DEFAULT_CASES
    for name, args in cases.items():
        frame, passes = [], {}
        for r in range(a.rounds):
            first, second = (a.old, a.new) if r % 2 == 0 else (a.new, a.old)
            res = {first: render(first, args), second: render(second, args)}
            frame.append(res[a.new][0] / res[a.old][0])
            for p, ms in res[a.new][1].items():
                if res[a.old][1].get(p, 0) > 0:
                    passes.setdefault(p, []).append(ms / res[a.old][1][p])
        q = statistics.quantiles(frame, n=4)
        detail = "  ".join(f"{p} {statistics.median(v):.2f}" for p, v in passes.items())
        print(f"{name:18s} new/old {statistics.median(frame):.3f} "
              f"(quartiles {q[0]:.3f}..{q[2]:.3f}, {a.rounds} rounds)  {detail}", flush=True)


if __name__ == "__main__":
    main()
