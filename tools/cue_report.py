#!/usr/bin/env python3
"""Writes docs/cue.md: the cue strike against Alciatore's proofs, squirt and swerve
tables, the planner against a cushion (tools/cue_report), the planner's side usage on
seeded tables (snooker plan --json, now and, when a binary of the level-cue planner
is given, before) and self-play with the robot's cue.

usage: cue_report.py TOOL SNOOKER DATA_DIR OUT_MD COMMAND COMMIT [BEFORE_SNOOKER]
Environment: TABLES (default 120), SELFPLAY_FRAMES (default 0: keep the saved run),
UNCERTAIN_FRAMES (default 0: keep the saved self-play in a world unlike the model).
"""
import json
import os
import statistics
import subprocess
import sys
import tempfile

from report_machine import machine

R = 0.02625


def run(args):
    return subprocess.run(args, check=True, capture_output=True, text=True).stdout


def side_usage(snooker, tables, level_cue):
    rows = []
    for k, path in enumerate(tables):
        out = json.loads(run([snooker, "plan", "--table", path, "--json", "--shots", "1", "--seed", "1",
                              "--budget-ms", "60000", "--max-simulations", "2400"]))
        if not out["shots"]:
            continue
        s = out["shots"][0]
        if s.get("kind", "POT") != "POT":
            continue
        if level_cue:  # the level cue of the ball-terms planner: w R / v = 5/2 b
            side = s["sidespin"] * R / (2.5 * s["speed"]) if s["speed"] > 0 else 0.0
            height, elevation = s["topspin"] * R / (2.5 * s["speed"]) if s["speed"] > 0 else 0.0, 0.0
        else:
            side, height, elevation = s["cue"]["tipSide"], s["cue"]["tipHeight"], s["cue"]["elevationDeg"]
        rows.append({"table": k, "cutDeg": s["cutDeg"], "tipSide": side, "tipHeight": height,
                     "elevationDeg": elevation, "positionValue": s["positionValue"],
                     "potProbability": s["potProbability"], "nextBall": s["nextBall"]})
    return rows


def quantiles(xs):
    if not xs:
        return "-", "-", "-"
    xs = sorted(xs)
    q = lambda p: xs[min(len(xs) - 1, int(p * len(xs)))]
    return f"{statistics.median(xs):.3f}", f"{q(0.9):.3f}", f"{xs[-1]:.3f}"


def usage_rows(name, rows):
    straight = [abs(r["tipSide"]) for r in rows if abs(r["cutDeg"]) < 5]
    every = [abs(r["tipSide"]) for r in rows]
    big = sum(1 for x in every if x >= 0.45 * 0.2)
    out = []
    for label, xs in (("cut under 5 deg", straight), ("every pot", every)):
        m, p90, mx = quantiles(xs)
        out.append(f"| {name} | {label} | {len(xs)} | {m} | {p90} | {mx} |")
    return out, big, len(every)


# Self-play where the world and the planner's belief about it differ: (name, the world
# uncertain, the squirt and throw uncertainty the planner is told).
UNCERTAIN_WORLDS = [("exact-told-exact", False, 0.0, 0.0), ("exact-told-rough", False, 0.15, 0.10),
                    ("rough-told-rough", True, 0.15, 0.10)]
UNCERTAIN_SEEDS = [1, 3]


def uncertain_args(seed, frames, world, squirt, throw):
    args = ["selfplay", "--frames", str(frames), "--seed", str(seed), "--threads", "1", "--budget-ms", "30000",
            "--max-simulations", "4000", "--squirt-uncertainty", str(squirt), "--throw-uncertainty", str(throw),
            "--json"]
    return args + (["--uncertain-world"] if world else [])


def uncertain_rows(data, frames, snooker):
    """Runs (frames > 0) or reads the self-play of UNCERTAIN_WORLDS, now and as saved
    from before the search priced the model's uncertainty; returns the table's rows."""
    rows = []
    for name, world, squirt, throw in UNCERTAIN_WORLDS:
        for when in ("before", "now"):
            runs = []
            for seed in UNCERTAIN_SEEDS:
                path = os.path.join(data, f"cue-uncertain-{name}-seed-{seed}{'-before' if when == 'before' else ''}.json")
                if when == "now" and frames > 0:
                    open(path, "w").write(run([snooker] + uncertain_args(seed, frames, world, squirt, throw)))
                runs.append(json.load(open(path)))
            shots = sum(r["shots"] for r in runs)
            pots = sum(round(r["potRate"] * r["shots"]) for r in runs)
            breaks = " / ".join(f"{r['meanBreak']:.1f}" for r in runs)
            mean = statistics.mean(r["meanBreak"] for r in runs)
            rows.append(f"| {'a real table' if world else 'the model'} | "
                        f"{'exact' if squirt == 0 and throw == 0 else f'{100 * squirt:.0f} % and {100 * throw:.0f} %'} | "
                        f"{when} | {runs[0]['frames']} + {runs[1]['frames']} | {breaks} ({mean:.1f}) | "
                        f"{100 * pots / shots:.1f} % of {shots} | {runs[0]['planMsP50']:.0f} / {runs[0]['planMsP99']:.0f} |")
    return "\n".join(rows)


def main():
    tool, snooker, data, out_md, command, commit = sys.argv[1:7]
    before = sys.argv[7] if len(sys.argv) > 7 else ""
    n = int(os.environ.get("TABLES", "120"))
    frames = int(os.environ.get("SELFPLAY_FRAMES", "0"))
    uncertain = uncertain_rows(data, int(os.environ.get("UNCERTAIN_FRAMES", "0")), snooker)
    strike = run([tool, "strike"])
    cushion = run([tool, "cushion"])
    with tempfile.TemporaryDirectory() as tmp:
        run([tool, "tables", tmp, str(n), "1"])
        tables = [os.path.join(tmp, f"table-{k}.json") for k in range(n)]
        after = side_usage(snooker, tables, False)
        # Where a straight pot takes side: the same table with side capped at 0.1 R.
        for r in after:
            if abs(r["cutDeg"]) < 5 and abs(r["tipSide"]) > 0.1:
                capped = json.loads(run([snooker, "plan", "--table", tables[r["table"]], "--json", "--shots", "1",
                                         "--seed", "1", "--budget-ms", "60000", "--max-simulations", "2400",
                                         "--max-sidespin", "0.25"]))
                s = capped["shots"][0] if capped["shots"] else None
                r["capped"] = {"kind": s["kind"] if s else "none", "positionValue": s["positionValue"] if s else 0,
                               "potProbability": s["potProbability"] if s else 0}
        json.dump(after, open(os.path.join(data, "cue-side-after.json"), "w"), indent=1)
        if before:
            json.dump(side_usage(before, tables, True), open(os.path.join(data, "cue-side-before.json"), "w"), indent=1)
    before_rows = json.load(open(os.path.join(data, "cue-side-before.json")))
    if frames > 0:
        base = [snooker, "selfplay", "--frames", str(frames), "--seed", "1", "--budget-ms", "80",
                "--noise-position-mm", "0.2", "--json"]
        open(os.path.join(data, "cue-selfplay.json"), "w").write(run(base))
        # The cue's noise at the level-cue planner's heading noise: aim 0.014 deg and
        # 0.07 mm of tip placement (0.014 deg of squirt) make 0.020 deg together.
        open(os.path.join(data, "cue-selfplay-equal-heading.json"), "w").write(
            run(base + ["--noise-aim-deg", "0.014", "--noise-tip-mm", "0.07"]))
    match_frames = int(os.environ.get("MATCH_FRAMES", "0"))
    if match_frames > 0:
        # The stall count's match at the frame-play reference noise (on the cue ball
        # alone, the cue's own noise 0), with the robot's cue.
        open(os.path.join(data, "cue-match-direct-pots.json"), "w").write(run(
            [snooker, "match", "--frames", str(match_frames), "--seed", "1", "--player-a", "default",
             "--player-b", "direct-pots", "--budget-ms", "80", "--noise-heading-deg", "0.02", "--noise-speed",
             "0.01", "--noise-spin", "2", "--noise-aim-deg", "0", "--noise-cue-speed", "0", "--noise-tip-mm", "0",
             "--noise-elevation-deg", "0", "--noise-position-mm", "0.2", "--json"]))
    m = json.load(open(os.path.join(data, "cue-match-direct-pots.json")))
    if frames > 0:
        # At docs/frame-play.md's reference noise, on the cue ball alone.
        open(os.path.join(data, "cue-selfplay-reference-noise.json"), "w").write(run(
            base + ["--noise-heading-deg", "0.02", "--noise-speed", "0.01", "--noise-spin", "2",
                    "--noise-aim-deg", "0", "--noise-cue-speed", "0", "--noise-tip-mm", "0",
                    "--noise-elevation-deg", "0"]))
    sp_ref = json.load(open(os.path.join(data, "cue-selfplay-reference-noise.json")))
    sp_after = json.load(open(os.path.join(data, "cue-selfplay.json")))
    sp_equal = json.load(open(os.path.join(data, "cue-selfplay-equal-heading.json")))
    sp_before = json.load(open(os.path.join(data, "cue-before-selfplay-level-cue.json")))

    lines_before, big_b, all_b = usage_rows("before: level cue, cue-ball noise", before_rows)
    lines_after, big_a, all_a = usage_rows("now: the robot's cue and its noise", after)
    straight_side = [r for r in after if abs(r["cutDeg"]) < 5 and abs(r["tipSide"]) > 0.1]
    # The capped plan is better when its pot is likelier and its position nearly as good.
    better = [r for r in straight_side
              if r["capped"]["potProbability"] > r["potProbability"] and
              r["capped"]["positionValue"] >= 0.9 * r["positionValue"]]
    verdict = (f"In {len(better)} of these {len(straight_side)} the capped plan finds a likelier pot with nearly "
               f"the same position (at least 0.9 of it): there the side did not pay, and the search, at 2400 "
               f"simulations, missed the plainer shot in the wider box." if better else
               "In none of these does the capped plan find a likelier pot with nearly the same position."
               if straight_side else "No straight pot takes more than 0.1 R of side.")
    text = open(os.path.join(os.path.dirname(__file__), "cue_report_text.md")).read()
    doc = text.format(
        command=command, commit=commit, strike=strike.strip(), cushion=cushion.strip(), tables=n,
        usage="\n".join(lines_before + lines_after), big_before=big_b, all_before=all_b, big_after=big_a,
        all_after=all_a, verdict=verdict,
        m_frames=m["frames"], m_won=m["framesWonA"], m_lost=m["framesWonB"], m_stalls=m["stallsA"],
        m_stalls_b=m["stallsB"], m_fouls=m["foulsA"], m_shots=m["shotsA"], m_break=m["meanBreakA"],
        m_break_b=m["meanBreakB"], m_p50=m["planMsP50A"], m_p99=m["planMsP99A"],
        straight_side="\n".join(
            f"| {r['table']} | {r['cutDeg']:.1f} | {r['tipSide']:.3f} | {r['tipHeight']:.3f} | "
            f"{r['potProbability']:.2f} | {r['positionValue']:.2f} | {r['capped']['kind']} | "
            f"{r['capped']['potProbability']:.2f} | {r['capped']['positionValue']:.2f} |"
            for r in straight_side) or "| - | - | - | - | - | - | - | - | - |",
        sp_frames_b=sp_before["frames"], sp_break_b=sp_before["meanBreak"], sp_rate_b=100 * sp_before["potRate"],
        sp_frames_a=sp_after["frames"], sp_break_a=sp_after["meanBreak"], sp_rate_a=100 * sp_after["potRate"],
        sp_p50_a=sp_after["planMsP50"], sp_p99_a=sp_after["planMsP99"],
        sp_frames_r=sp_ref["frames"], sp_break_r=sp_ref["meanBreak"], sp_rate_r=100 * sp_ref["potRate"],
        sp_p50_r=sp_ref["planMsP50"], sp_p99_r=sp_ref["planMsP99"],
        sp_frames_e=sp_equal["frames"], sp_break_e=sp_equal["meanBreak"], sp_rate_e=100 * sp_equal["potRate"],
        sp_p50_e=sp_equal["planMsP50"], sp_p99_e=sp_equal["planMsP99"],
        sp_p50_b=sp_before["planMsP50"], sp_p99_b=sp_before["planMsP99"], uncertain=uncertain,
        uncertain_command=" ".join(["snooker"] + uncertain_args("S", "N", True, 0.15, 0.10)), machine=machine())
    open(out_md, "w").write(doc)


if __name__ == "__main__":
    main()
