#!/usr/bin/python3
"""Writes docs/planner.md and its plots from the measurements in docs/data/.

Usage: tools/planner_report.py DATA_DIR DOCS_DIR COMMAND [REVISION]
Reads planner-selfplay.json, planner-estimate-0.2.json, planner-estimate-0.5.json,
planner-fidelity.json, planner-search.json and planner-bench.json (made by
scripts/planner-report, the COMMAND named in the document) and writes
DOCS_DIR/planner.md, DOCS_DIR/planner-budget.svg and DOCS_DIR/planner-estimate.svg.
REVISION, the git commit whose code was measured, is named in the document.
"""
import json
import os
import re
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from report_machine import machine


def load(data, name):
    with open(os.path.join(data, name)) as f:
        return json.load(f)


def records(data, run):
    """The run's frame records (selfplay --records), or None when it has none."""
    path = os.path.join(data, run.get("records", ""))
    if not run.get("records") or not os.path.exists(path):
        return None
    with open(path) as f:
        return [json.loads(line) for line in f]


def mean_se(pts):
    """The standard error of the mean of pts."""
    m = sum(pts) / len(pts)
    return (sum((p - m) ** 2 for p in pts) / (len(pts) - 1)) ** 0.5 / len(pts) ** 0.5


def ends(data, run):
    """How the run's breaks ended: counts of cleared, miss, foul, no pot (and of those,
    no pot from the frame's first shot)."""
    out = {"cleared": 0, "miss": 0, "foul": 0, "no pot": 0, "no pot at once": 0, "shot cap": 0}
    recs = records(data, run)
    if recs is None:
        return None
    for rec in recs:
        end = rec["end"]
        key = "foul" if end.startswith("foul") else end
        out[key] = out.get(key, 0) + 1
        if end == "no pot" and rec["attempts"] == 0:
            out["no pot at once"] += 1
    return out


def first_frames(data, run, n):
    """The run's first n frames (from its records) in the form of a self-play result,
    so runs of different lengths compare on the same tables. Planning times are the
    whole run's."""
    recs = records(data, run)
    if recs is None:
        return run["result"]
    recs = recs[:n]
    shots = sum(r["attempts"] for r in recs)
    out = dict(run["result"])
    out.update({"frames": len(recs), "shots": shots,
                "meanBreak": sum(r["points"] for r in recs) / len(recs),
                "maxBreak": max(r["points"] for r in recs),
                "potRate": sum(r["pots"] for r in recs) / shots if shots else 0})
    return out


def selfplay_table(runs, names, data):
    out = ("| run | command | frames | shots | mean break | largest | pots dropped | "
           "plan p50 (ms) | plan p99 (ms) | breaks ended: cleared / miss / foul / no pot (at once) | "
           "load (1/5/15 min) |\n"
           "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---|\n")
    for name in names:
        r = runs[name]
        x = r["result"]
        e = ends(data, r)
        e_text = (f"{e['cleared']} / {e['miss']} / {e['foul']} / {e['no pot']} ({e['no pot at once']})"
                  if e else "?")
        out += (f"| {name} | `{r['command']}` | {x['frames']} | {x['shots']} | {x['meanBreak']:.1f} | "
                f"{x['maxBreak']} | {100 * x['potRate']:.1f} % | {x['planMsP50']:.1f} | "
                f"{x['planMsP99']:.1f} | {e_text} | {r.get('load', '?')} |\n")
    return out


def pool(data, seed_runs):
    """Mean break, pot rate and the mean's standard error over all frames of the runs
    (one per seed), from their records; `over` says what they pooled when more than one."""
    recs = []
    for run in seed_runs:
        run_recs = records(data, run)
        if run_recs is None:  # the first run's own figures
            x = seed_runs[0]["result"]
            return {"meanBreak": x["meanBreak"], "potRate": x["potRate"], "se": float("nan"), "over": ""}
        recs += run_recs
    pts = [r["points"] for r in recs]
    mean = sum(pts) / len(pts)
    se = mean_se(pts)
    shots = sum(r["attempts"] for r in recs)
    over = f" over the {len(pts)} frames of seeds 1 to {len(seed_runs)}" if len(seed_runs) > 1 else ""
    return {"meanBreak": mean, "potRate": sum(r["pots"] for r in recs) / shots if shots else 0,
            "se": se, "over": over}


def break_se(data, run, n):
    """Standard error of the mean break over the run's first n frames."""
    recs = records(data, run)
    return mean_se([r["points"] for r in recs[:n]]) if recs is not None else 0.0


def budget_plot(runs, budgets, path, data, frames):
    xs = [b for b, _ in budgets]
    res = [first_frames(data, runs[n], frames) for _, n in budgets]
    se = [break_se(data, runs[n], frames) for _, n in budgets]
    fig, ax = plt.subplots(1, 2, figsize=(10, 4))
    ax[0].errorbar(xs, [r["meanBreak"] for r in res], yerr=se, fmt="o-", color="#1a7f37",
                   capsize=3, label="mean break +- 1 standard error")
    ax[0].set_xscale("log")
    ax[0].set_xlabel("planning budget per shot (ms)")
    ax[0].set_ylabel("mean break (points)", color="#1a7f37")
    ax2 = ax[0].twinx()
    ax2.plot(xs, [100 * r["potRate"] for r in res], "s--", color="#c0161c")
    ax2.set_ylabel("attempted pots that dropped (%)", color="#c0161c")
    ax[0].set_title(f"Answer quality against budget ({frames} frames each)")
    ax[1].plot(xs, [r["planMsP50"] for r in res], "o-", label="p50")
    ax[1].plot(xs, [r["planMsP99"] for r in res], "s--", label="p99")
    ax[1].plot(xs, xs, ":", color="grey", label="budget")
    ax[1].set_xscale("log")
    ax[1].set_yscale("log")
    ax[1].set_xlabel("planning budget per shot (ms)")
    ax[1].set_ylabel("planning time per shot (ms)")
    ax[1].legend()
    ax[1].set_title("Planning time against budget")
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def estimate_stats(est, nominal_only=False):
    pots = [p for p in est["pots"] if p["nominal"] or not nominal_only]
    diffs = [p["estimate"] - p["monte_carlo"] for p in pots]
    n = len(pots)
    mean_abs = sum(abs(d) for d in diffs) / n
    bias = sum(diffs) / n
    worst = max(abs(d) for d in diffs)
    within = sum(1 for d in diffs if abs(d) <= 0.1) / n
    # By cut: the estimate is first order in the geometry; thin cuts are where it errs.
    bins = [(0, 30), (30, 50), (50, 70), (70, 90)]
    by_cut = []
    for lo, hi in bins:
        sel = [abs(p["estimate"] - p["monte_carlo"]) for p in pots if lo <= abs(p["cut_deg"]) < hi]
        if sel:
            by_cut.append((lo, hi, len(sel), sum(sel) / len(sel), max(sel)))
    return n, mean_abs, bias, worst, within, by_cut


def estimate_plot(ests, path):
    fig, ax = plt.subplots(figsize=(5, 5))
    for (mm, est), c in zip(ests, ["#1f4fd1", "#c0161c"]):
        ax.scatter([p["monte_carlo"] for p in est["pots"]], [p["estimate"] for p in est["pots"]],
                   s=10, alpha=0.6, color=c, label=f"{mm} mm vision noise")
    ax.plot([0, 1], [0, 1], ":", color="grey")
    ax.set_xlabel(f"Monte Carlo with the full simulator ({ests[0][1]['samples']} samples)")
    ax.set_ylabel("fast estimate")
    ax.set_title("Pot probability: estimate against Monte Carlo")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def bench_rows(bench):
    rows = []
    for b in bench["benchmarks"]:
        if b.get("run_type") != "iteration" or not b["name"].startswith("BM_PlanBudget/"):
            continue
        _, budget, reds = b["name"].split("/")[:3]
        rows.append((int(budget), int(reds), b))
    return sorted(rows)


def schedule(header="planner/planner.h"):
    """PlannerConfig's budget shares and the simulations a millisecond buys, as the
    planner's header sets them (the document describes the code, not a copy of it)."""
    with open(header) as f:
        text = f.read()
    names = ["simulations_per_ms", "search_share", "lookahead_share", "monte_carlo_share", "end_share"]
    values = {}
    for name in names:
        m = re.search(r"\bdouble %s = ([0-9.]+);" % name, text)
        if m is None:
            sys.exit("planner_report: no PlannerConfig::%s in %s" % (name, header))
        values[name] = float(m.group(1))
    return values


def main():
    data, docs, command = sys.argv[1], sys.argv[2], sys.argv[3]
    revision = sys.argv[4] if len(sys.argv) > 4 else "?"
    sp = load(data, "planner-selfplay.json")
    runs = {r["name"]: r for r in sp["runs"]}
    est2 = load(data, "planner-estimate-0.2.json")
    est5 = load(data, "planner-estimate-0.5.json")
    fid = load(data, "planner-fidelity.json")
    search = load(data, "planner-search.json")
    bench = load(data, "planner-bench.json")

    budgets = [(10, "budget 10 ms"), (30, "budget 30 ms"), (80, "default"),
               (100, "budget 100 ms"), (300, "budget 300 ms")]
    budget_plot(runs, budgets, os.path.join(docs, "planner-budget.svg"), data, sp["frames"])
    estimate_plot([(0.2, est2), (0.5, est5)], os.path.join(docs, "planner-estimate.svg"))

    d = runs["default"]["result"]
    # The default settings on every seed played (seed 1 alone in older data): the
    # targets' mean break and pot rate are over all their frames.
    seed_runs = [r for r in sp["runs"] if r["name"] == "default" or r["name"].startswith("default, seed ")]
    pooled = pool(data, seed_runs)
    seeds_text = ""
    if len(seed_runs) > 1:
        seeds_text = ("\nThe default settings' runs on seeds 1 to %d broke %s on average (%.1f over their\n"
                      "%d frames, standard error %.1f)." % (len(seed_runs),
                                            ", ".join("%.1f" % r["result"]["meanBreak"] for r in seed_runs[:-1]) + " and %.1f" % seed_runs[-1]["result"]["meanBreak"],
                                            pooled["meanBreak"],
                                            sum(r["result"]["frames"] for r in seed_runs), pooled["se"]))
    # The comparisons use the default run's first frames: the same tables as theirs.
    d_same = first_frames(data, runs["default"], sp["frames"])
    half = runs["position 0.5 mm"]["result"]
    pot = runs["pot only"]["result"]
    room = runs["cue clearance 5 cm"]["result"]
    ratio = d_same["meanBreak"] / pot["meanBreak"] if pot["meanBreak"] > 0 else float("inf")
    se = float("nan")
    d_ends = ends(data, runs["default"]) or {}
    blocks = []
    if (d_recs := records(data, runs["default"])) is not None:
        pts = [r["points"] for r in d_recs]
        se = mean_se(pts)
        blocks = [sum(pts[k:k + 100]) / len(pts[k:k + 100]) for k in range(0, len(pts), 100)]
    by_budget = [(b, first_frames(data, runs[n], sp["frames"])) for b, n in budgets]
    # Are the budgets' mean breaks further apart than two standard errors of a run?
    se_run = se * (d["frames"] / sp["frames"]) ** 0.5
    breaks = [x["meanBreak"] for _, x in by_budget]
    if max(breaks) - min(breaks) <= 2 * se_run:
        budget_headline = "A larger budget does not buy a longer break."
        budget_spread = "within about two standard errors of one run of each other"
    else:
        budget_headline = "The budget moves the mean break by more than the runs' noise."
        budget_spread = f"further apart than two standard errors of one run ({2 * se_run:.1f})"
    variants = {v["variant"]: v for v in search["variants"]}
    default_v = variants.get("DIRECT-L + BOBYQA (default)")
    locals_ = [v["mean_score"] for k, v in variants.items() if k.startswith("DIRECT-L +") and "geometric" not in k]
    no_throw = next((v for k, v in variants.items() if "geometric" in k), None)
    bobyqa_only = variants.get("BOBYQA only")

    def status(ok):
        return "met" if ok else "**missed**"

    targets = (
        "| target | reached (default noise, default budget 80 ms) | |\n|---|---|---|\n"
        f"| planning p50 < 100 ms | {d['planMsP50']:.1f} ms | {status(d['planMsP50'] < 100)} |\n"
        f"| planning p99 < 500 ms | {d['planMsP99']:.1f} ms | {status(d['planMsP99'] < 500)} |\n"
        f"| >= 95 % of attempted pots drop | {100 * pooled['potRate']:.1f} %{pooled['over']} | "
        f"{status(pooled['potRate'] >= 0.95)} |\n"
        f"| mean break >= 50 | {pooled['meanBreak']:.1f}{pooled['over']} (standard error {pooled['se']:.1f}) | "
        f"{status(pooled['meanBreak'] >= 50)} |\n"
        f"| position play at least doubles the pot-only mean break | {ratio:.1f}x ({d_same['meanBreak']:.1f} against "
        f"{pot['meanBreak']:.1f} on the same first {sp['frames']} frames) | {status(ratio >= 2)} |\n")

    est_table = ("| vision noise | pots | mean abs difference | mean difference (bias) | largest | within 0.10 |\n"
                 "|---|---:|---:|---:|---:|---:|\n")
    for mm, est in ((0.2, est2), (0.5, est5)):
        for nominal_only in (False, True):
            n, m, b, w, wi, _ = estimate_stats(est, nominal_only)
            what = " (the assumed shot pots without noise)" if nominal_only else " (all)"
            est_table += f"| {mm} mm{what} | {n} | {m:.3f} | {b:+.3f} | {w:.3f} | {100 * wi:.0f} % |\n"
    cut2 = estimate_stats(est2)[5]
    cut_table = "| cut (deg) | pots | mean abs difference | largest |\n|---|---:|---:|---:|\n"
    for lo, hi, n, m, w in cut2:
        cut_table += f"| {lo}-{hi} | {n} | {m:.3f} | {w:.3f} |\n"

    fid_rows = fid["settings"]
    def fid_row(name, early, tolerance=None):
        return next(s for s in fid_rows if s["setting"] == name and s["early_stop"] == early
                    and (tolerance is None or s["tolerance"] == tolerance))
    base = fid_row("the default tier", False)
    search_tier = fid_row("the search's tier", True)
    fine = fid_row("solvers only", False, 1e-10)
    fine_early = fid_row("solvers only", True, 1e-10)
    same = fid_row("solvers only", False, base["tolerance"])
    fid_table = ("| setting | impact tolerance | impact tables | early stop | CPU us per shot | relative cost | "
                 "events per shot | verdicts changed | object-ball lines changed by > 0.1 mm | largest line change (mm) | "
                 "median / mean / largest change of the cue ball's end (mm) |\n"
                 "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---|\n")
    for s in fid_rows:
        fid_table += (f"| {s['setting']} | {s['tolerance']:g} | {'yes' if s['impact_tables'] else 'no'} | "
                      f"{'yes' if s['early_stop'] else 'no'} | {s['cpu_us_per_shot']:.0f} | "
                      f"{s['cpu_us_per_shot'] / base['cpu_us_per_shot']:.2f} | {s['events_per_shot']:.2f} | "
                      f"{s['verdicts_changed']} of {fid['shots']} | {s['lines_changed_over_0_1_mm']} of "
                      f"{s['lines_compared']} | {s['max_line_offset_change_mm']:.1f} | "
                      f"{s['median_cue_end_change_mm']:.4f} / {s['mean_cue_end_change_mm']:.3f} / "
                      f"{s['max_cue_end_change_mm']:.1f} |\n")

    search_table = ("| search | mean objective of the best shot (points) | its pot probability | tables with a shot | "
                    "NLopt evaluations per plan |\n|---|---:|---:|---:|---:|\n")
    for v in search["variants"]:
        search_table += (f"| {v['variant']} | {v['mean_score']:.2f} | {100 * v['mean_pot']:.1f} % | "
                         f"{v['found']:.0f} of {search['tables']} | {v['evaluations_per_plan']:.0f} |\n")

    bench_table = ("| budget (ms) | balls | plans | elapsed / budget: median | 99th percentile | largest | "
                   "simulations per plan | shots found |\n|---:|---:|---:|---:|---:|---:|---:|---:|\n")
    for budget, reds, b in bench_rows(bench):
        bench_table += (f"| {budget} | {reds + 7} | {b['iterations']} | {b['elapsed_p50']:.2f} | "
                        f"{b['elapsed_p99']:.2f} | {b['elapsed_max']:.2f} | {b['simulations']:.0f} | "
                        f"{b['shots']:.2f} |\n")
    work = next((b for b in bench["benchmarks"] if b["name"].startswith("BM_PlanWork")), None)
    rows = bench_rows(bench)
    p99_10 = max((b["elapsed_p99"] for budget, _, b in rows if budget == 10), default=float("nan"))
    p99_rest = max((b["elapsed_p99"] for budget, _, b in rows if budget > 10), default=float("nan"))
    ctx = bench["context"]
    sched = schedule()
    pct = lambda share: "%.0f %%" % (100 * share)  # noqa: E731
    # What a thread simulates a millisecond when the cap binds (two threads).
    work_rate = 1e3 / work["wall_us_per_simulation"] / 2 if work else float("nan")

    sweep = ("| budget (ms) | mean break | largest | pots dropped | plan p50 (ms) | plan p99 (ms) |\n"
             "|---:|---:|---:|---:|---:|---:|\n")
    for b, name in budgets:
        x = first_frames(data, runs[name], sp["frames"])
        sweep += (f"| {b} | {x['meanBreak']:.1f} | {x['maxBreak']} | {100 * x['potRate']:.1f} % | "
                  f"{x['planMsP50']:.1f} | {x['planMsP99']:.1f} |\n")

    doc = f"""# The shot planner

Generated by `{command}` (do not edit by hand; the measurements are in `docs/data/planner-*.json`).
Measured on the code of commit `{revision}`.
Machine: {machine()}; shared with other developers' builds and tests while it ran
(load averages in the tables), so times are upper bounds. Build: Release (-O3, `scripts/dev build`).

## Results against the targets

{targets}
Self-play is `snooker selfplay` ({d['frames']} frames at the default settings{' on each of seeds 1 to ' + str(len(seed_runs)) if len(seed_runs) > 1 else ''}, {sp['frames']} for the
other runs; seed 1, so every run's first {sp['frames']} frames start from the same tables):
random mid-frame tables of
6 to 10 reds with the colours on their spots (up to 17 balls; the budget benchmark below
also plans 22-ball tables), the planner seeing every ball through 0.2 mm of vision noise
and its best shot played with the default execution noise, judged by the rules. A
break ends at a miss, a foul, a table with no pot for the planner, or a cleared table.

## How it plans

`planner/planner.h` runs, within the budget:

1. **Candidates** (`candidates.h`): every legal object ball with every pocket, pruned by
   geometry before any search: cuts over 80 deg (and impossible ones), a pocket closed to
   that direction (its simulated acceptance window is empty), the cue ball's path to the
   ghost-ball position or the object ball's path to the mouth passing within 2R + 0.5 mm
   of another ball, and no room for the robot's level cue behind the cue ball (a ball or
   a cushion within 10 cm along the stroke).
2. **Search** (`search.h`): per candidate, NLopt over speed, topspin, sidespin and cut in
   the unit cube (the spins as fractions of the rolling spin, within the robot's limits).
   The cut is the collision model's prediction of the aim that sends the object ball down
   the planned line (the ghost-ball cut corrected for throw: three Newton steps on
   `ResolveBallBallOnTable` for the cue ball as it arrives) plus a correction of at most
   0.6 deg that the search sets from the simulation. GN_DIRECT_L explores speed and spin
   (deterministic, bound-constrained, evenly spread at a few dozen evaluations: stun,
   follow and screw leave the cue ball in different places), then LN_BOBYQA refines all
   four (a quadratic model fits the smooth Gaussian pot probability around the cut
   ridge in few evaluations; at equal work the three local algorithms tried score
   within {100 * (max(locals_) - min(locals_)) / max(locals_):.1f} % of each other, see below). The
   objective of a shot that pots in its (early-stopping, looser-tolerance) simulation is
   P x (value + position): P its pot probability from its simulated object-ball line
   under noise, position the expected points of the position left (`position.h`:
   weights 1, 0.33, 0.15 on the best next shots by the rules, one per ball, each worth
   its value plus the break value, 30 points unless the request sets `break_value`;
   discounted for a cue ball on a cushion or cramped by a ball behind it). A failed shot
   scores -1 + P/2, a barrier that still points towards a centred line. Candidates are
   ranked by their fast estimate of expected points, p (value + break value), and share
   the search's simulations by rank (the first four a full share, the next four half,
   up to twelve a quarter; none under a tenth of the best).
3. **Verification**: each candidate's best shot is simulated again at full fidelity to
   the end; it is dropped if it fails there. No shot leaves the planner that its own
   full simulation says fails.
4. **Robustness** (`robustness.h`): seeded Monte Carlo (48 samples by default, in blocks
   of 8 with their own random streams) of the best few under execution and vision noise,
   full simulator; the ranking is the Monte Carlo mean of the objective, and
   potProbability the Monte Carlo success rate.

Anytime: the search keeps its best verified shot apart from NLopt's iterate, reports it
through the progress callback each time it improves, and every phase stops at its share
of the budget (the search to {pct(sched["search_share"] - sched["lookahead_share"])} and the lookahead's search of the next shot
to {pct(sched["search_share"])}, or the search to {pct(sched["search_share"])} without it; the Monte Carlo to
{pct(sched["search_share"] + sched["monte_carlo_share"])}; everything by {pct(sched["end_share"])}), at the caller's deadline or when the cancel flag is set.
Work is also capped in simulations derived from the budget ({sched["simulations_per_ms"]:.0f} per ms per thread,
the answer's `simulation_cap`), and NLopt's tolerances end most searches sooner still:
unless time runs out first, the same seed gives the same answer whatever the thread
timing, and the same request capped at `simulation_cap` gives it on any machine
(tests check both); when time does run out (the answer's `cut_short`), the answer is
the best found in time. A plan whose searches all run to their caps simulates about
{work_rate:.0f} times a millisecond a thread (BM_PlanWork, below), fewer than the cap assumes, so
on tables with many candidates the clock, not the cap, ends it. Two worker threads
share the candidates and the Monte Carlo blocks, one simulator each.

Once the buffers have grown, no evaluation allocates: a worker keeps its simulators,
the table a stroke leaves and its copy with the cue ball in hand (`LeaveScratch`) from
one candidate's search to the next, and the Monte Carlo's sampled and final positions
(`SampleScratch`) from block to block.
`tests/planner/allocation_test.cc` counts the global `operator new` over a second
evaluation of each kind (a pot's leave, a re-spot, a safety, an in-off handed over in
hand, a block of eight samples) and asserts zero.

Both scratches also keep the object balls' lines into the pockets (`PocketLineCache`,
`pot_estimate.h`). A line depends on the ball's place, the pocket and the arrival
speed alone, so a position valued again with balls that have not moved (the position
spread's two sides, the placements in the D, most of a search's strokes) takes it
from the cache: the same line to the bit, looked up by exact keys, and the same plans
(tests in `pot_estimate_test.cc` and `position_test.cc`). Paired runs of
`build/bench/planner_bench --benchmark_filter=BM_PlanWork/400/ --benchmark_repetitions=1`
before and after, eight of each alternately, gave a median CPU time a plan of 6.70 ms
against 7.22 (0.94) and, with the position spread at 2, 8.20 against 9.56 (0.87). An
outlook with the cue ball in hand values the same object balls from every point of its
grid in the D, and keeps a cache for the call when its caller has none:
`build/bench/planner_outlook_bench --benchmark_filter=BM_EvaluateOutlookInHand` went
from 464 to 285 us a call (medians of five runs of each, alternately).

## Self-play

{selfplay_table(runs, [r['name'] for r in seed_runs] + ['position 0.5 mm', 'pot only', 'cue clearance 5 cm'], data)}
What position play is worth: the same planner with the position term switched off
(`--pot-only`: the objective is P x value, the most likely points now) breaks
{pot['meanBreak']:.1f} on average against {d_same['meanBreak']:.1f} on the same {sp['frames']} tables
({ratio:.1f}x), and its pots drop less often ({100 * pot['potRate']:.1f} % against
{100 * d_same['potRate']:.1f} %): not choosing where the
cue ball stops, it leaves itself harder pots, or none. At 0.5 mm of vision noise (2.5x
the default) the mean break is {half['meanBreak']:.1f} and {100 * half['potRate']:.1f} % of pots drop:
vision error dominates a pot's error (an object ball 0.5 mm off where vision put it
leaves about 0.5 deg off line; docs/planning-notes.md §2), and over a metre that is
most of the pocket's tolerance. The standard error of the default run's mean break is
{se:.1f} points ({d['frames']} frames, seed 1); of a 100-frame run's about {se * (d['frames'] / 100) ** 0.5:.1f}: differences
smaller than twice that are noise.{seeds_text} The same frames played twice give the same
breaks only where no plan meets its budget: the work such a plan does depends on the
time it gets (the budget binds at 10 ms, and on a shared machine), so its shot, and
everything after it, differ. The default run's
first {sp['frames']} frames broke {d_same['meanBreak']:.1f} on average here; its three blocks of 100
frames {', '.join('%.1f' % x for x in blocks)}.

## Answer quality against budget

![quality and time against budget](planner-budget.svg)

{sweep}
{selfplay_table(runs, [n for _, n in budgets if n != 'default'], data)}
## Elapsed time against budget

Google Benchmark `bench/planner_bench` (`BM_PlanBudget/<budget ms>/<reds>`): 64 seeded
tables per row (8 reds: 15 balls; 15 reds: 22 balls, the colours on their spots), one plan
each, wall time over the budget.

{bench_table}
{"Whole-planner cost at a binding simulation cap (BM_PlanWork, 2 threads): %.0f us of wall time per simulation, including the search's throw prediction and position values, verification and Monte Carlo." % work["wall_us_per_simulation"] if work else ""}
Benchmark machine: {ctx.get('host_name', '?')}, {ctx.get('num_cpus', '?')} CPUs, load average
{', '.join('%.2f' % x for x in ctx.get('load_avg', []))} at the start.

## The fast pot-probability estimate against Monte Carlo

`planner/pot_estimate.h` turns each error into a sideways shift of the object ball's
line at the mouth to first order (heading, each ball's position, and the throw that spin
and speed noise add, from `throw_model.h`), and integrates the resulting Gaussian over
the pocket's acceptance window for that direction and speed (`pocket_model.h`: measured
by rolling single balls at each pocket, bisecting each edge to 0.08 mm). Against 400
noisy full simulations of the plain rolling pot it assumes (struck rolling, fast enough
to bring the object ball to the mouth at 0.5 m/s, aimed with the throw predicted), on
seeded two-ball positions (every pocket the candidates keep; `tools/planner_report
estimate`), counting the object ball's drops:

{est_table}
By cut (0.2 mm):

{cut_table}
![estimate against Monte Carlo](planner-estimate.svg)

The largest differences are long thin cuts whose assumed rolling shot does not pot
even without noise (the object ball needs more speed than the estimate's typical speed,
capped at 5 m/s, gives it): the estimate judges the line, not the speed. The test
`PotEstimateTest.AgreesWithMonteCarloOnASetOfPositions` holds it to 0.15 per position
and 0.06 on average (cuts up to 70 deg, 200 samples). The estimate ranks the
candidates and values positions; the final ranking and the potProbability returned are
the Monte Carlo's.

In the search the estimate is taken from each stroke's simulated line rather than the
plain rolling pot (`planner/search.cc`), and it also prices what the Monte Carlo samples
beyond the geometry: the squirt and the throw that the model knows only to a fraction
(`SquirtSigma`, `ThrowSigma`; docs/cue.md, "A table the model knows only roughly"). It
still judges the line, not the speed: a ball that only just drops is rated as one that
drops firmly (docs/whole-frame-planner.md §10 measures pricing that too).

## Fidelity: what the search's cheaper settings cost and change

The planner simulates at two tiers (`physics/sim/fidelity.h`): the search at the search
tier (the impact solvers at 1e-6, the impact tables where they apply) and stopping a run
as soon as its verdict is known (`planner/shot_sim.h`: the first contact is not the
object ball, the cue ball or a ball not on drops, the object ball or the untouched cue
ball comes to rest); verification and the Monte Carlo at the default tier (1e-7 and the
impact tables), run to the end. {fid['shots']} search-like shots (every candidate of 40
seeded frames, four speeds and spins each) against the converged tier (DOP853 at
1e-12, every impact solved), run to the end; the solvers alone at a sweep of tolerances
for comparison (`tools/planner_report fidelity`; CPU time, fastest of 5 passes; cost
relative to the default tier without the early stop):

{fid_table}
CPU times on this shared machine move by 10 % or so from run to run, so only the
large steps are real: the search's tier costs {search_tier['cpu_us_per_shot'] / base['cpu_us_per_shot']:.2f} of the
default tier, and the default tier {base['cpu_us_per_shot'] / fine['cpu_us_per_shot']:.2f} of the solvers alone at 1e-10.
No verdict changes at either tier. The impact tables add nothing to the default tier's
error: the solvers alone at its tolerance change {same['lines_changed_over_0_1_mm']} lines and move the cue ball's end
by {same['mean_cue_end_change_mm']:.3f} mm on average, where the tier with the tables changes {base['lines_changed_over_0_1_mm']} and moves it
{base['mean_cue_end_change_mm']:.3f} mm, at {base['cpu_us_per_shot'] / same['cpu_us_per_shot']:.2f} of their cost. The object ball's line and the cue ball's end are
unchanged on most shots (medians of micrometres); the largest changes come from the few
shots where the cue ball or the object ball kisses a third ball or runs along a
cushion, which amplify the differences of the looser settings into centimetres (the
solvers alone at 1e-10 stay within {fine['max_cue_end_change_mm']:.1f} mm of the converged tier). That is why every returned shot is verified, and its events and end
position come from the default tier's run. The early stop ends
{100 * (1 - fine_early['events_per_shot'] / fine['events_per_shot']):.1f} % fewer events on this set (a shot that pots runs to
the end: where the cue ball stops is the point), a saving within the timing noise here;
it never changes a verdict (it ends only runs already decided; the test
`ShotSimTest.StoppingEarlyNeverChangesTheVerdict` checks it), but a run it stops reports the
object ball's line from its last contact before the stop, where the run to the end may
see a later one (a kiss after the verdict), which is why a few lines differ with it even
at 1e-10.

## Search choices at equal work

{search['tables']} seeded tables, {search['simulations_per_plan']} simulations per plan, each
variant's best shot judged by an independent Monte Carlo ({search['judge_samples']}
samples) of the same objective (`tools/planner_report search`):

{search_table}
## Defaults and why

The runs above play the robot's cue (`physics/cue/`): the execution noise is the cue's
(aim 0.02 deg, speed 1 %, tip placement 0.1 mm, elevation 0.1 deg), the model's squirt
and throw uncertainty 0 (self-play's world is the model itself), and the vision noise
below. The cue-ball terms of the table (heading, speed and spin noise) were the
planner's execution noise before it had a cue; they remain as extra noise on the cue
ball, 0 by default, and frame-play.md's reference noise is made of them. The cue's
defaults and reasons are in [cue.md](cue.md).

| | default | why |
|---|---|---|
| heading noise | 0.02 deg | snooker's long pots need a few hundredths of a degree: over 1.5 m + 1.5 m a straight pot drops 63 % at 0.025 deg and 14 % at the pool tournaments' 0.125 deg (docs/planning-notes.md §2); a good robot arm with a calibrated cue reaches 0.02 deg |
| speed noise | 1 % | a servo-driven cue's repeatability; speed matters for position, little for the pot |
| spin noise | 2 rad/s (topspin and sidespin) | about half a millimetre of tip offset at 1 m/s (spin = 5 v b / 2R^2 for an offset b); it turns the object ball through throw, for a full-ball contact about 0.5 deg at 0.3 m/s and 0.13 deg at 1.2 m/s (ThrowModel) |
| vision noise | 0.2 mm per axis per ball | what calibrated overhead cameras can reach; published systems reach about 4 mm (pix2pockets). For a straight pot 1 m from the pocket, 0.2 mm on each ball moves the object ball's line by about 5.5 mm at the mouth, as much as the heading noise does with the cue ball 1 m back (6 mm); at 0.5 mm vision dominates |
| speed range | 0.3 to 6 m/s | from a soft roll to a firm positional shot (a break-off is about 7-10 m/s) |
| spin | topspin within the rolling spin, sidespin within half of it | a tip offset of about half the radius gives 1.25x the rolling spin; the robot keeps a margin against miscues |
| cue room | 10 cm of clear bed behind the cue ball, 7 mm stick radius | a level cue at the ball's centre height cannot pass over the cushion (36 mm nose) or a ball |
| budget | 80 ms | the p50 target is 100 ms; phases and caps leave room for the last simulation in flight |
| Monte Carlo | 48 samples per ranked shot | a success rate to about +-3 % at 0.95 |

## What limits it

- **{budget_headline}** From
  {by_budget[0][0]} to {by_budget[-1][0]} ms the runs' mean breaks on the same {sp['frames']} tables lie between
  {min(x['meanBreak'] for b, x in by_budget):.1f} and {max(x['meanBreak'] for b, x in by_budget):.1f} ({by_budget[0][1]['meanBreak']:.1f} at {by_budget[0][0]} ms), {budget_spread}. Each candidate's search converges (NLopt's tolerances)
  before a large budget is spent (the simulations per plan in the benchmark below grow
  ever slower with the budget), and what is left is the noise's share. The search
  optimises the nominal shot's position, and more of it can find positions the noise
  does not keep (a cue ball that ends just right after two cushions); the Monte Carlo
  ranking sees that, but only among the few shots it ranks. Nearly all of a plan's time
  is simulation (in a profile, perf, of `planner_bench --benchmark_filter=BM_PlanWork/400/0`
  on commit 026f14a, the event search, event times recomputed and their polynomials'
  roots, took about a quarter of a plan's CPU time, the cushion impact's integrator
  about 14 % and the ball-ball impact's about 7 %), so a faster
  simulator buys more search in the same budget (docs/selfplay-before-after.md
  measures the default run on a faster one).
- **Missed pots** end most breaks ({d_ends.get('miss', '?')} of {d['frames']}; {d_ends.get('foul', '?')} end by a foul):
  {100 * (1 - d['potRate']):.1f} % of attempted pots miss. The planner takes the shot with the best
  expected points, which trades a little pot probability for position; the Monte Carlo
  success rates it ranks by are estimates (48 samples), and the best of a few is a
  little optimistic. Vision noise matters most: at 0.5 mm the pot rate falls to
  {100 * half['potRate']:.1f} %.
- **Breaks that end with no pot** ({d_ends.get('no pot', '?')} of {d['frames']}, of which
  {d_ends.get('no pot at once', '?')} at the frame's first shot): {'some random frames start with no pot the robot can play (every path blocked, or no room for the cue), and ' if d_ends.get('no pot at once') else 'with the cue raised over a ball or cushion where a level one has no room (cue.md) no frame of this run started without a pot; '}position play
  sometimes leaves none once the noise has moved the cue ball. With 5 cm of clear bed for the cue instead
  of 10 cm the mean break is {room['meanBreak']:.1f} (against {d_same['meanBreak']:.1f} on the same
  {sp['frames']} tables) and {(ends(data, runs['cue clearance 5 cm']) or {}).get('no pot at once', '?')} frames start with no pot.
- **Search choices** matter little: at {search['simulations_per_plan']} simulations per plan the local
  algorithms score alike; the global stage is worth
  {(default_v['mean_score'] - bobyqa_only['mean_score']) if default_v and bobyqa_only else float('nan'):+.2f} points of objective per shot against BOBYQA alone
  (pot probability {100 * default_v['mean_pot'] if default_v else float('nan'):.1f} % against {100 * bobyqa_only['mean_pot'] if bobyqa_only else float('nan'):.1f} %),
  and the throw prediction {(default_v['mean_score'] - no_throw['mean_score']) if default_v and no_throw else float('nan'):+.2f} (without it the search must find the throw
  correction itself within its 0.6 deg range, so thin cuts are lost).
- **Elapsed time** is the scheduler's as much as the planner's: over the benchmark
  above (load average {', '.join('%.2f' % x for x in ctx.get('load_avg', []))} at its start) the 99th percentile of
  elapsed / budget is {p99_10:.2f} at 10 ms and at most {p99_rest:.2f} from 30 ms on. At 10 ms the
  two worker threads waiting for a core and the simulation in flight when time runs out
  are a large share of the budget (under a heavier load, 5 to 8, a run has taken
  twice the budget there).
- **Estimate**: first order in the geometry; on cuts beyond 70 deg its error grows (table
  above), so thin cuts are ranked by the Monte Carlo only.
"""
    with open(os.path.join(docs, "planner.md"), "w") as f:
        f.write(doc)
    print(doc)


if __name__ == "__main__":
    main()
