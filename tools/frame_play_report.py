#!/usr/bin/python3
"""Writes docs/frame-play.md from the `snooker match --json` outputs of scripts/frame-play.

Usage: tools/frame_play_report.py DATA_DIR OUTPUT COMMAND [REVISION]
       tools/frame_play_report.py --handover STROKES.jsonl[.gz]...
Reads DATA_DIR/frame-play-<opponent>-<vision>-mm.json (and the wall time in the .time
file beside each, and the stroke log of `snooker match --strokes`, gzipped, in the
.strokes.jsonl.gz file, when there are) for the opponents direct-pots and one-ply and the
vision noises 0.2 and 0.5 mm, and the noise scan against direct-pots
(frame-play-direct-pots-noise-<scale>.json, the reference noise scaled by 0.5 and
0.25); the matches missing are left out, none is an error.
COMMAND is the command that made the data, REVISION the commit measured; both are
named in the document. With --handover it prints only the table of what player A's
strokes that handed the table over left (handover_table), what player B's stalls
gave back (returns_line) and, when the logs carry the plans' predictions, how often
A's strokes handed the table over against them (prediction_table), over the stroke
logs given.
Standard library only.
"""
import gzip
import json
import math
import os
import sys

from report_machine import machine

OPPONENTS = ("direct-pots", "one-ply")
VISION_MM = ("0.2", "0.5")
PLAYERS = {
    "default": "the planner with every shot kind, pot route and the lookahead",
    "direct-pots": "direct pots only, without the lookahead",
    "one-ply": "the default without the lookahead",
}


def load(data_dir):
    """The matches found, in a fixed order: (opponent, vision, json, wall seconds or None)."""
    runs = []
    for opponent in OPPONENTS:
        for vision in VISION_MM:
            base = os.path.join(data_dir, f"frame-play-{opponent}-{vision}-mm")
            if not os.path.exists(base + ".json"):
                continue
            with open(base + ".json") as f:
                d = json.load(f)
            wall = None
            if os.path.exists(base + ".time"):
                with open(base + ".time") as f:
                    wall = float(f.read().strip())
            runs.append((opponent, vision, d, wall))
    return runs


# The noise scan: default against direct-pots with the reference noise scaled down
# (execution and vision alike), frame-play-direct-pots-noise-<scale>.json.
NOISE_SCALES = ("0.5", "0.25")


def load_noise_scan(data_dir):
    """The noise scan's matches found: (scale, json), largest noise first."""
    runs = []
    for scale in NOISE_SCALES:
        path = os.path.join(data_dir, f"frame-play-direct-pots-noise-{scale}.json")
        if os.path.exists(path):
            with open(path) as f:
                runs.append((scale, json.load(f)))
    return runs


def noise_scan_section(runs, scan):
    """The default's share against direct-pots as the noise shrinks: the reference
    match, then the scan's."""
    reference = [d for o, v, d, w in runs if o == "direct-pots" and v == "0.2"]
    if not scan or not reference:
        return ""
    rows = [("1", reference[0])] + list(scan)
    out = "\n## Against direct-pots at less noise\n\n"
    out += ("The same match with the reference noise scaled down, the execution's and the vision's alike "
            "(`scripts/frame-play` plays them beside the others, same seed and budget): how the default's "
            "share depends on how precisely the robot strikes and sees.\n\n")
    out += ("| noise, of the reference | heading deg | speed % | spins rad/s | vision mm | frames "
            "| default's share of decided frames (95 %) | mean break A | mean break B | centuries A | "
            "B's turns without a direct pot |\n|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|\n")
    for scale, d in rows:
        out += (f"| {scale} | {d['noiseHeadingDeg']:g} | {100 * d['noiseSpeed']:g} | {d['noiseSpin']:g} | "
                f"{d['noisePositionMm']:g} | {d['frames']} | {share(d)} | {d['meanBreakA']:.1f} | "
                f"{d['meanBreakB']:.1f} | {d['centuriesA']} | {d['stallsB']} |\n")
    met = [scale for scale, d in rows if (won_share(d) or 0) >= 0.8]
    out += ("\nBoth players pot with the same search; what separates them is the turns `direct-pots` has no "
            "direct pot and the misses that hand either the table. With less noise both miss less, and the "
            "default's safeties and the turns `direct-pots` has no pot decide more of the frames. ")
    if met and met[0] == "1":
        out += "The 80 % target is met at the reference noise.\n"
    elif met:
        out += f"The 80 % target is reached at {met[0]} of the reference noise, not at the reference itself.\n"
    else:
        out += "The 80 % target is not reached at any of these noises.\n"
    return out


def load_strokes(data_dir, opponent, vision):
    """The stroke log of a match (a list of dicts, in the order of play), or None."""
    path = os.path.join(data_dir, f"frame-play-{opponent}-{vision}-mm.strokes.jsonl.gz")
    if not os.path.exists(path):
        return None
    with gzip.open(path, "rt") as f:
        return [json.loads(line) for line in f if line.strip()]


def frames_of(strokes):
    """The log's strokes by frame, in frame order."""
    frames = {}
    for s in strokes:
        frames.setdefault(s["frame"], []).append(s)
    return [frames[k] for k in sorted(frames)]


def visits_of(frame):
    """A frame's visits: (striker, points scored, its strokes)."""
    visits = []
    for s in frame:
        if not visits or visits[-1][0] != s["striker"]:
            visits.append([s["striker"], 0, []])
        visits[-1][1] += s["points"]
        visits[-1][2].append(s)
    return visits


# What handed the winner the visit that won the frame: the loser's last stroke before it.
CAUSES = (
    ("stall", "the loser had no shot (no pot for direct-pots: the straight shot at the nearest ball on)"),
    ("miss high", "the loser missed a pot its plan rated at least 0.9"),
    ("miss low", "the loser missed a pot its plan rated below 0.9"),
    ("foul", "the loser fouled"),
    ("safety", "after the loser's safety or escape"),
    ("break-off", "after the loser's break-off"),
    ("first", "the winner's own first visit (it broke off and scored)"),
)


def handover(last):
    """What a visit's last stroke, which handed the table over, was: CAUSES' key."""
    if last["stall"]:
        return "stall"
    if last["foul"] != "none":
        return "foul"
    if last["turn"] == "break-off":
        return "break-off"
    if last["kind"] == "POT":
        p = last["potProbability"]
        return "miss high" if p is not None and p >= 0.9 else "miss low"
    return "safety"


def cause(visits, k):
    """Why visit k came to its striker: CAUSES' key."""
    return "first" if k == 0 else handover(visits[k - 1][2][-1])


# How a scoring visit ended: its last stroke (the frame's end when it was the frame's last).
ENDINGS = (
    ("frame end", "the frame ended"),
    ("miss high", "a missed pot the plan rated at least 0.9"),
    ("miss low", "a missed pot the plan rated below 0.9"),
    ("foul", "a foul"),
    ("safety", "a safety or escape"),
    ("break-off", "a break-off"),
    ("stall", "no shot (the straight shot at the nearest ball on)"),
)

# The bins of the plan's pot probability, as [low, high).
POT_BINS = ((0.0, 0.5), (0.5, 0.7), (0.7, 0.8), (0.8, 0.9), (0.9, 0.95), (0.95, 1.01))


def bin_of(bins, x):
    """The index of the [low, high) bin of `bins` that holds x, or None."""
    return next((i for i, (lo, hi) in enumerate(bins) if lo <= x < hi), None)


def potted(stroke):
    """Whether a pot stroke dropped a ball on: it scored and was no foul."""
    return stroke["points"] > 0 and stroke["foul"] == "none"


def endings_table(frames, a, b):
    """How each player's scoring visits ended, with their mean points."""
    tally = {side: {key: [] for key, _ in ENDINGS} for side in "AB"}
    for frame in frames:
        visits = visits_of(frame)
        for k, (striker, points, strokes) in enumerate(visits):
            if points == 0:
                continue
            key = "frame end" if k == len(visits) - 1 else handover(strokes[-1])
            tally[striker][key].append(points)
    out = f"| a scoring visit ended with | `{a}`: visits | mean break | `{b}`: visits | mean break |\n|---|---:|---:|---:|---:|\n"
    for key, what in ENDINGS:
        cells = []
        for side in "AB":
            v = tally[side][key]
            cells += [str(len(v)), f"{sum(v) / len(v):.1f}" if v else "-"]
        out += f"| {what} | " + " | ".join(cells) + " |\n"
    return out


def calibration_bins(frames):
    """Per player and POT_BINS bin: [pots, pots that dropped, sum of the plans' probabilities]."""
    bins = {side: [[0, 0, 0.0] for _ in POT_BINS] for side in "AB"}
    for frame in frames:
        for s in frame:
            p = s["potProbability"]
            if s["kind"] != "POT" or s["stall"] or p is None:
                continue
            i = bin_of(POT_BINS, p)
            if i is not None:
                cell = bins[s["striker"]][i]
                cell[0] += 1
                cell[1] += potted(s)
                cell[2] += p
    return bins


def calibration_table(bins, a, b):
    """The plan's pot probability against the pots' played results, per player."""
    out = (f"| plan's pot probability | `{a}`: pots | planned | dropped | `{b}`: pots | planned | dropped |\n"
           "|---|---:|---:|---:|---:|---:|---:|\n")
    for i, (lo, hi) in enumerate(POT_BINS):
        cells = []
        for side in "AB":
            n, ok, psum = bins[side][i]
            cells += [str(n), f"{psum / n:.3f}" if n else "-", f"{ok / n:.3f}" if n else "-"]
        out += f"| {lo:.2f}-{min(hi, 1.0):.2f} | " + " | ".join(cells) + " |\n"
    return out


# The bins of the incoming player's best pot probability after a handover, as [low, high).
HANDOVER_BINS = ((0.0, 0.02), (0.02, 0.5), (0.5, 0.8), (0.8, 0.95), (0.95, 1.01))
HANDOVER_KINDS = (("miss", "a missed pot"), ("safety", "a safety or escape"), ("break-off", "the break-off"),
                  ("any", "any stroke"))


def handovers(frames, side):
    """Each time `side` handed the table over: (its visit's last stroke, the opponent's
    next visit as visits_of gives it), over the frames given."""
    for frame in frames:
        visits = visits_of(frame)
        for k in range(len(visits) - 1):
            if visits[k][0] == side:
                yield visits[k][2][-1], visits[k + 1]


def handover_bins(frames, side="A"):
    """Per kind of `side`'s stroke that handed the table over (HANDOVER_KINDS, stalls and
    fouls apart) and HANDOVER_BINS bin of its handoverPot: [strokes, sum of handoverPot,
    the opponent's next strokes that were pots, of them those that dropped, the points of
    the opponent's visit]. Strokes without the field are skipped."""
    bins = {key: [[0, 0.0, 0, 0, 0] for _ in HANDOVER_BINS] for key, _ in HANDOVER_KINDS}
    for last, (_, next_points, next_strokes) in handovers(frames, side):
        p = last.get("handoverPot")
        if p is None:
            continue
        key = handover(last)
        if key in ("stall", "foul"):
            continue
        key = "miss" if key.startswith("miss") else key
        nxt = next_strokes[0]
        attempt = not nxt["stall"] and nxt["kind"] == "POT"
        i = bin_of(HANDOVER_BINS, p)
        if i is not None:
            for cell in (bins[key][i], bins["any"][i]):
                cell[0] += 1
                cell[1] += p
                cell[2] += attempt
                cell[3] += attempt and potted(nxt)
                cell[4] += next_points
    return bins


def handover_table(bins, b):
    """What player A's handovers left against what the opponent `b` then did."""
    out = (f"| A's stroke | outlook bin | strokes | outlook, mean | `{b}` played a pot | it dropped | "
           f"`{b}`'s visit, mean points |\n|---|---|---:|---:|---:|---:|---:|\n")
    for key, what in HANDOVER_KINDS:
        for i, (lo, hi) in enumerate(HANDOVER_BINS):
            n, psum, tried, dropped, points = bins[key][i]
            if n:
                out += (f"| {what} | {lo:.2f}-{min(hi, 1.0):.2f} | {n} | {psum / n:.3f} | {tried / n:.2f} | "
                        f"{dropped / n:.2f} | {points / n:.1f} |\n")
    return out


PREDICTION_BINS = ((0.0, 0.05), (0.05, 0.5), (0.5, 0.95), (0.95, 1.01))


def prediction_bins(frames, side="A"):
    """Per PREDICTION_BINS bin of the chance that `side`'s stroke hands the table over
    as its plan's Monte Carlo predicted it (planHandovers: runs over samples), stalls
    and the frames' last strokes apart: [strokes, sum of the predicted chance, strokes
    that handed it over, of those the ones with both outlooks, the sum of the plan's
    mean best pot for the opponent over its runs that handed over, the sum of the
    handoverPot measured on the table left]. Strokes without the field are skipped."""
    bins = [[0, 0.0, 0, 0, 0.0, 0.0] for _ in PREDICTION_BINS]
    for frame in frames:
        for k, stroke in enumerate(frame[:-1]):
            h = stroke.get("planHandovers")
            if stroke["striker"] != side or h is None or not h["samples"]:
                continue
            rate = h["runs"] / h["samples"]
            cell = bins[bin_of(PREDICTION_BINS, rate)]
            cell[0] += 1
            cell[1] += rate
            if frame[k + 1]["striker"] != side:
                cell[2] += 1
                if h["runs"] and stroke.get("handoverPot") is not None:
                    cell[3] += 1
                    cell[4] += h["meanPotProbability"]
                    cell[5] += stroke["handoverPot"]
    return bins


def prediction_table(bins, a):
    """How often `a`'s strokes handed the table over against its plans' predictions."""
    out = (f"| the plan's chance of handing over | `{a}`'s strokes | predicted, mean | handed over | "
           "of those, with the plan's and the table's outlook | the opponent's best pot: planned | "
           "on the table left |\n|---|---:|---:|---:|---:|---:|---:|\n")
    for (lo, hi), (n, rate, handed, both, planned, measured) in zip(PREDICTION_BINS, bins):
        if n:
            out += (f"| {lo:.2f}-{min(hi, 1.0):.2f} | {n} | {rate / n:.3f} | {handed / n:.3f} | {both} | "
                    f"{number(planned / both if both else None, 3)} | {number(measured / both if both else None, 3)} |\n")
    return out


def returns_line(frames, side="B"):
    """What `side`'s stalls gave back: the strokes it played without a shot of its own
    (for direct-pots, the straight shot at the nearest ball on when it has no direct
    pot; the break-off apart), the penalties of those that fouled, and the points of the
    other player's next visit, over the frames given."""
    n = fouls = penalty = points = 0
    for last, (_, next_points, _) in handovers(frames, side):
        if not last["stall"] or last["turn"] == "break-off":
            continue
        n += 1
        if last["foul"] != "none":
            fouls += 1
            penalty += last["penalty"]
        points += next_points
    if not n:
        return f"`{side}` played no stroke without a shot of its own.\n"
    return (f"After `{side}`'s {n} strokes without a shot of its own ({fouls} of them fouls, "
            f"{penalty / n:.1f} points of penalty a stroke), the next visit scored {points / n:.1f} points "
            f"a stroke: together {(penalty + points) / n:.1f}.\n")


def stalls_paragraph(strokes, d):
    """The default's stalls in a match's stroke log, each with the plan's reason (logs
    before the reason was logged give none)."""
    if not strokes:
        return ""
    stalls = [s for s in strokes if s["stall"] and s["striker"] == "A"]
    if not stalls:
        return (f"\n`{d['playerA']}` had no stall in this match's {d['frames']} frames "
                f"({d['shotsA']} strokes).\n")
    out = f"\n`{d['playerA']}`'s stalls in this match, with what its plan said:\n\n"
    for s in stalls:
        reason = s.get("stallReason", "(not logged)")
        out += f"- frame {s['frame']}, stroke {s['stroke']} ({s['turn']}, on {s.get('stallOn', '?').lower()}): {reason}\n"
    return out


def decided_section(strokes, d):
    """How the frames of a match were decided, from its stroke log."""
    if not strokes:
        return ""
    frames = frames_of(strokes)
    by_breaker = {"A": [0, 0], "B": [0, 0]}
    answer = {"A": {"potted": 0, "missed": 0, "stall": 0}, "B": {"potted": 0, "missed": 0, "stall": 0}}
    causes = {key: [0, 0] for key, _ in CAUSES}
    for frame in frames:
        last = frame[-1]
        breaker = frame[0]["striker"]
        if len(frame) > 1 and frame[1]["striker"] != breaker:
            nxt = frame[1]
            kind = "stall" if nxt["stall"] else ("potted" if nxt["points"] > 0 else "missed")
            answer[breaker][kind] += 1
        if last["scoreA"] == last["scoreB"]:
            continue
        winner = "A" if last["scoreA"] > last["scoreB"] else "B"
        by_breaker[breaker][0 if winner == "A" else 1] += 1
        visits = visits_of(frame)
        best = max((k for k, v in enumerate(visits) if v[0] == winner), key=lambda k: visits[k][1])
        causes[cause(visits, best)][0 if winner == "A" else 1] += 1
    a, b = d["playerA"], d["playerB"]
    out = "\n## How the frames were decided\n\n"
    out += ("From the match's stroke log (`snooker match --strokes`, saved gzipped beside its JSON). "
            f"By who broke off: when `{a}` broke off it won {by_breaker['A'][0]} of "
            f"{sum(by_breaker['A'])} decided frames, when `{b}` did, {by_breaker['B'][0]} of "
            f"{sum(by_breaker['B'])}. The stroke after each break-off that handed the table over: after `{a}`'s, "
            f"`{b}` potted a ball {answer['A']['potted']} times, missed a pot {answer['A']['missed']} times and "
            f"had no pot {answer['A']['stall']} times; after `{b}`'s, `{a}` potted {answer['B']['potted']} "
            f"times and missed or played another kind of shot {answer['B']['missed']} times.\n\n")
    out += ("A frame's winning visit is the winner's highest-scoring one; what handed it the table is the "
            "loser's last stroke before it.\n\n")
    out += f"| what handed the winner its winning visit | frames won by `{a}` | frames won by `{b}` |\n|---|---:|---:|\n"
    for key, what in CAUSES:
        out += f"| {what} | {causes[key][0]} | {causes[key][1]} |\n"
    lost = sum(v[1] for v in causes.values())
    if lost:
        missed = causes["miss high"][1] + causes["miss low"][1]
        out += (f"\nOf the {lost} frames `{b}` won, {missed} came after `{a}` missed a pot "
                f"({causes['miss high'][1]} of them rated at least 0.9 by its plan), {causes['foul'][1]} after its "
                f"fouls and {causes['safety'][1]} after its safeties. Of the {sum(v[0] for v in causes.values())} "
                f"`{a}` won, {causes['stall'][0]} came after `{b}` had no pot"
                f"{' (its straight shot at the nearest ball on)' if causes['stall'][0] else ''}: `{a}` wins where "
                f"`{b}` plays a different game from its own, and loses after its own misses and safeties, against an opponent "
                "that is its own pot search.\n")
    out += ("\nHow the visits that scored ended (a visit that ended the frame is counted there, whatever "
            "its last stroke):\n\n")
    out += endings_table(frames, a, b)
    out += ("\nThe plan's pot probability (its Monte Carlo) against what the pots it chose did when played, "
            "stalls apart. A ball on that dropped counts, on any route; the planned column is the mean of "
            "the plans' probabilities in the bin.\n\n")
    bins = calibration_bins(frames)
    out += calibration_table(bins, a, b)
    # The last bin: the pots rated at least 0.95.
    n, ok, psum = bins["A"][-1]
    if n:
        planned, dropped, expected, missed = psum / n, ok / n, n - psum, n - ok
        out += (f"\n`{a}`'s {n} pots rated at least 0.95 dropped {100 * dropped:.1f} % of the time against "
                f"{100 * planned:.1f} % planned: its plans expected {expected:.0f} misses among them and {missed} "
                "happened. Most of its misses of near-certain pots are the execution and vision noise the Monte "
                "Carlo counts; the rest is the small optimism of taking the best of a few estimates (48 samples "
                "each). Each miss hands the table to an opponent that pots as well as it does.\n")
    if any(s.get("handoverPot") is not None for s in strokes):
        out += (f"\nWhat `{a}`'s strokes that handed the table over left `{b}`: the outlook is its best pot "
                "probability by the planner's fast estimate (what the plans score a miss or a safety by), against "
                f"whether `{b}`'s next stroke was a pot, whether that dropped, and the points of its visit.\n\n")
        out += handover_table(handover_bins(frames), b)
    if any(s.get("planHandovers") is not None for s in strokes):
        out += (f"\nHow often `{a}`'s strokes handed the table over, against the chance its plans' Monte Carlo "
                "gave (the runs that handed it over, of the samples), stalls and the frames' last strokes apart; "
                "and, where both are known, the opponent's best pot as the plan's handing-over runs left it "
                "against the same estimate on the table the stroke left.\n\n")
        out += prediction_table(prediction_bins(frames), a)
    return out


def wilson(wins, n, z=1.96):
    """The 95 % Wilson score interval of a share, as (low, high); None when n is 0."""
    if n == 0:
        return None
    p = wins / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n)) / (1 + z * z / n)
    return max(0.0, centre - half), min(1.0, centre + half)


def won_share(d):
    """A's share of the decided frames, or None when none was decided."""
    decided = d["framesWonA"] + d["framesWonB"]
    return d["framesWonA"] / decided if decided else None


def share(d):
    decided = d["framesWonA"] + d["framesWonB"]
    interval = wilson(d["framesWonA"], decided)
    if interval is None:
        return "-"
    return f"{100 * d['framesWonA'] / decided:.0f} % ({100 * interval[0]:.0f}-{100 * interval[1]:.0f} %)"


def number(x, digits=1):
    return "-" if x is None else f"{x:.{digits}f}"


def summary_table(runs):
    out = ("| A against B | vision | frames | won A | won B | level | A's share of decided frames (95 %) "
           "| points A | points B | stalls | frames at the cap | plan ms p50 | p99 | wall s |\n"
           "|---|---:|---:|---:|---:|---:|---|---:|---:|---:|---:|---:|---:|---:|\n")
    for opponent, vision, d, wall in runs:
        out += (f"| {d['playerA']} against {d['playerB']} | {vision} mm | {d['frames']} | {d['framesWonA']} | "
                f"{d['framesWonB']} | {d['framesUndecided']} | {share(d)} | {d['pointsA']} | {d['pointsB']} | "
                f"{d['stalls']} | {d['framesCapped']} | {number(d['planMsP50'])} | {number(d['planMsP99'])} | "
                f"{number(wall, 0)} |\n")
    return out


def player_table(d):
    rows = [
        ("frames won", "framesWon", 0),
        ("points", "points", 0),
        ("of them from the opponent's fouls", "penaltyPoints", 0),
        ("mean break", "meanBreak", 1),
        ("highest break", "highestBreak", 0),
        ("centuries", "centuries", 0),
        ("fouls", "fouls", 0),
        ("safeties played", "safeties", 0),
        ("strokes", "shots", 0),
        ("stalls", "stalls", 0),
        ("planning ms, median", "planMsP50", 1),
        ("planning ms, 99th percentile", "planMsP99", 1),
        ("opponent's best pot after a safety, mean", "safetyOutlook", 2),
        ("opponent's best pot after a safety, median", "safetyOutlookP50", 2),
        ("opponent's best pot after a break-off, mean", "breakOffOutlook", 2),
        ("opponent's best pot after a break-off, median", "breakOffOutlookP50", 2),
    ]
    out = f"| | A: {d['playerA']} | B: {d['playerB']} |\n|---|---:|---:|\n"
    for label, key, digits in rows:
        cells = []
        for side in "AB":
            v = d.get(key + side)
            cells.append("not measured" if v is None else (f"{v:.{digits}f}" if digits else f"{v}"))
        out += f"| {label} | {cells[0]} | {cells[1]} |\n"
    return out


def kinds_table(runs):
    """How often each kind of shot and each pot route was played, per player and match."""
    kinds = ("POT", "SAFETY", "ESCAPE", "BREAK_OFF", "FOUL")
    routes = ("DIRECT", "PLANT", "DOUBLE", "KICK")
    out = ("| match | player | " + " | ".join(k.lower().replace("_", "-") for k in kinds) + " | "
           + " | ".join(r.lower() for r in routes) + " | stalls | fouls per stroke |\n"
           + "|---|---|" + "---:|" * (len(kinds) + len(routes) + 2) + "\n")
    for opponent, vision, d, wall in runs:
        for side in "AB":
            k = d.get("kinds" + side) or {}
            r = d.get("routes" + side) or {}
            strokes = d.get("shots" + side) or 0
            fouls = d.get("fouls" + side) or 0
            rate = f"{100 * fouls / strokes:.1f} %" if strokes else "-"
            out += (f"| {d['playerA']} v {d['playerB']}, {vision} mm | {d['player' + side]} | "
                    + " | ".join(str(k.get(x, "-")) for x in kinds) + " | "
                    + " | ".join(str(r.get(x, 0)) for x in routes)
                    + f" | {d['stalls' + side]} | {rate} |\n")
    return out


def timing_table(runs):
    """Planning time by kind of turn, both players of each match."""
    turns = ("on table", "in hand", "break-off")
    out = ("| match | " + " | ".join(f"{t}: p50 / p99 ms" for t in turns) + " |\n|---|"
           + "---:|" * len(turns) + "\n")
    for opponent, vision, d, wall in runs:
        by = d.get("planMsByTurn") or {}
        cells = []
        for t in turns:
            x = by.get(t) or {}
            cells.append(f"{number(x.get('p50'))} / {number(x.get('p99'))}")
        out += f"| {d['playerA']} v {d['playerB']}, {vision} mm | " + " | ".join(cells) + " |\n"
    return out


def above_half(d):
    """Whether A's whole 95 % interval of the decided frames lies above one half."""
    interval = wilson(d["framesWonA"], d["framesWonA"] + d["framesWonB"])
    return interval is not None and interval[0] > 0.5


def targets_table(runs, selfplay):
    """The targets the planner is held to, each with what was measured."""
    rows = []
    def match(opponent, vision):
        for o, v, d, w in runs:
            if o == opponent and v == vision:
                return d
        return None
    stall_runs = [d for o, v, d, w in runs if o == "direct-pots" and v == "0.2"]
    if stall_runs:
        d = stall_runs[0]
        rows.append(("the default player stalls on no turn over at least 200 frames",
                     f"{d['stallsA']} stalls in {d['frames']} frames", d["stallsA"] == 0 and d["frames"] >= 200))
    fouls = sum(d["foulsA"] for o, v, d, w in runs if v == "0.2")
    strokes = sum(d["shotsA"] for o, v, d, w in runs if v == "0.2")
    if strokes:
        rows.append(("the default player fouls on at most 2 % of its strokes (reference noise)",
                     f"{100 * fouls / strokes:.1f} % ({fouls} of {strokes})", fouls <= 0.02 * strokes))
    for opponent, goal in (("direct-pots", 0.80), ("one-ply", 0.55)):
        d = match(opponent, "0.2")
        if d:
            rows.append((f"the default wins at least {100 * goal:.0f} % of frames against {opponent}",
                         share(d), (won_share(d) or 0) >= goal))
    medians = [d["safetyOutlookP50A"] for o, v, d, w in runs
               if v == "0.2" and d.get("safetyOutlookP50A") is not None]
    if medians:
        worst = max(medians)
        rows.append(("after the default's safeties the opponent's best pot has a median of at most 0.3",
                     ", ".join(f"{m:.2f}" for m in medians), worst <= 0.3))
    for label, d in selfplay:
        if label.startswith("default"):
            rows.append(("self-play: mean break at least 55, at least 96 % of attempted pots drop",
                         f"{d['meanBreak']:.1f}, {100 * d['potRate']:.1f} %",
                         d["meanBreak"] >= 55 and d["potRate"] >= 0.96))
    worst50 = worst99 = 0.0
    for o, v, d, w in runs:
        for x in (d.get("planMsByTurn") or {}).values():
            if x.get("p50") is not None:
                worst50 = max(worst50, x["p50"])
                worst99 = max(worst99, x["p99"])
    if runs:
        rows.append(("planning time p50 below 100 ms and p99 below 500 ms on every kind of turn",
                     f"worst p50 {worst50:.1f} ms, worst p99 {worst99:.1f} ms", worst50 < 100 and worst99 < 500))
    out = "| target | measured | |\n|---|---|---|\n"
    for what, measured, met in rows:
        out += f"| {what} | {measured} | {'met' if met else '**missed**'} |\n"
    return out


def lookahead_section(runs, selfplay):
    """What the lookahead buys and costs, from the default-against-one-ply matches and
    self-play with and without it."""
    rows = [(v, d) for o, v, d, w in runs if o == "one-ply"]
    if not rows:
        return ""
    out = "\n## What the lookahead buys, and what it costs\n\n"
    out += ("At equal time the lookahead moves 15 % of the budget from the search to searching the next shot "
            "of the two best pots (PlannerConfig::lookahead_share, lookahead_shots). Measured here:\n\n")
    for v, d in rows:
        out += (f"- against `one-ply` at {v} mm of vision noise the default takes {share(d)} of the decided "
                f"frames, mean break {d['meanBreakA']:.1f} against {d['meanBreakB']:.1f}, planning p50 "
                f"{d['planMsP50A']:.1f} against {d['planMsP50B']:.1f} ms;\n")
    sp = dict(selfplay)
    if "default (lookahead)" in sp and "one-ply" in sp:
        a, b = sp["default (lookahead)"], sp["one-ply"]
        out += (f"- in self-play the mean break is {a['meanBreak']:.1f} with it and {b['meanBreak']:.1f} without, "
                f"planning p50 {a['planMsP50']:.1f} and {b['planMsP50']:.1f} ms.\n")
    above = [(v, d) for v, d in rows if above_half(d)]
    reference = [d for v, d in rows if v == "0.2"]
    met = bool(reference) and (won_share(reference[0]) or 0) >= 0.55
    if above:
        out += ("\nSo the lookahead wins frames at equal time: at "
                + " and ".join(f"{v} mm" for v, d in above)
                + " of vision noise the whole 95 % interval of the default's share lies above one half. At the "
                "reference noise the 55 % target is " + ("met" if met else "**missed**") + ", with an interval "
                "that still reaches below one half: a hundred frames cannot tell 55 % from 50 %. It costs 15 % "
                "of the search's budget on every shot.\n")
    else:
        out += ("\nSo the lookahead buys nothing these runs can resolve, and takes 15 % of the budget from the "
                "search. Our reading (not measured apart): the searched next-pot probability replaces a fast "
                "estimate that already agrees with Monte Carlo on the short, open positions good position play "
                "leaves (docs/planner.md), so it seldom changes which pot ranks first, while the search loses "
                "evaluations on every shot.\n")
    return out


def lookahead_worth(runs):
    """A few words on what the one-ply matches resolve of the lookahead's worth."""
    rows = [d for o, v, d, w in runs if o == "one-ply"]
    return "is a few points of share" if any(above_half(d) for d in rows) else "is too small for a hundred frames to resolve"


def direct_pots_section(runs):
    """Why the default's share against direct-pots is what it is, from that match's figures."""
    rows = [d for o, v, d, w in runs if o == "direct-pots" and v == "0.2"]
    if not rows:
        return ""
    d = rows[0]
    decided = d["framesWonA"] + d["framesWonB"]
    if decided == 0 or d["shotsB"] == 0:
        return ""
    won = d["framesWonA"] / decided
    out = "\n## Against direct-pots\n\n"
    out += (f"The default takes {share(d)} of the decided frames against `direct-pots`"
            f"{'' if won >= 0.8 else ', short of the 80 % target'}. `direct-pots` is not a weak potter: it is this "
            "planner's own pot search, Monte Carlo, cue and position value, and it differs only where it has no "
            "direct pot. In this match that was "
            f"{d['stallsB']} of its {d['shotsB']} strokes ({100 * d['stallsB'] / d['shotsB']:.0f} %); there it "
            "plays a firm shot at the nearest ball on, and there the default gains: "
            f"{d['penaltyPointsA']} points from its fouls ({d['foulsB']} fouls against the default's "
            f"{d['foulsA']}), and {d['safetiesA']} safeties after which its best pot had a median probability of "
            f"{d['safetyOutlookP50A']:.2f}. On the visits that score, both pot like the strong players they are: "
            f"mean break {d['meanBreakA']:.1f} against {d['meanBreakB']:.1f}, centuries {d['centuriesA']} "
            f"against {d['centuriesB']}, highest {d['highestBreakA']} against {d['highestBreakB']}. Which turns "
            "decide the frames is below, from the match's stroke log. The target's anchor, the Deep Green robot, "
            "credits its 80 % to lookahead; here the "
            f"lookahead's worth against `one-ply` (below) {lookahead_worth(runs)}, where 80 % needs "
            f"{max(0.0, 80 - 100 * won):.0f} more points of share against `direct-pots`.\n")
    if d.get("breakOffOutlookA") is not None and d.get("breakOffOutlookB") is not None:
        out += ("\nThe break-off opens every frame. After the default's break-offs (the soft break into the "
                "pack: planner/break_off.h) "
                f"`direct-pots`' best pot had a mean probability of {d['breakOffOutlookA']:.2f} (median "
                f"{d['breakOffOutlookP50A']:.2f}); after `direct-pots`' own, a firm straight shot into the pack, the "
                f"default's had {d['breakOffOutlookB']:.2f} (median {d['breakOffOutlookP50B']:.2f}). Both by the "
                "planner's fast estimate on the table as it lay.\n")
    return out


def load_selfplay(data_dir):
    """Self-play runs saved beside the matches: (label, json) for each found."""
    runs = []
    for name, label in (("frame-play-selfplay", "default (lookahead)"),
                        ("frame-play-selfplay-one-ply", "one-ply")):
        path = os.path.join(data_dir, name + ".json")
        if os.path.exists(path):
            with open(path) as f:
                runs.append((label, json.load(f)))
    return runs


def selfplay_table(runs):
    out = ("| planner | frames | mean break | highest | attempted pots that dropped | plan ms p50 | p99 |\n"
           "|---|---:|---:|---:|---:|---:|---:|\n")
    for label, d in runs:
        out += (f"| {label} | {d['frames']} | {d['meanBreak']:.1f} | {d['maxBreak']} | "
                f"{100 * d['potRate']:.1f} % | {d['planMsP50']:.1f} | {d['planMsP99']:.1f} |\n")
    return out


def document(runs, command, revision, selfplay=(), strokes=None, scan=()):
    strokes = strokes or {}
    first = runs[0][2]
    frames = first["frames"]
    budget = first["budgetMs"]
    sims = first["maxSimulations"]
    out = f"""# Whole frames: the planner against weaker players

Generated by `{command}` on commit `{revision}` (do not edit by hand), from the
`snooker match --json` outputs saved in `docs/data/frame-play-*.json`. The players
plan and strike with the robot's cue (tip offsets, squirt, elevation: docs/cue.md); the
reference noise is put on the cue ball itself, the cue's own noise set to 0, so that the
figures compare with the level-cue runs before it.

Each match is `snooker match` (`planner/match.h`): two players play {frames} whole frames
of snooker by the rules as `planner/frame.h` applies them: the standard start with the
cue ball in hand for the break-off, fouls worth 4 to 7 to the opponent, the
touching-ball rule, the ball in hand after an in-off, re-spotting, the colours in order
once the reds are gone, and a re-spotted black when a frame ends level. The free ball
and the miss rule are not applied, and no ball can leave the simulated table. A frame
stopped at the shot cap (200 strokes) goes to the higher score, or to nobody when the
scores are level.

Player A breaks off in the first, third, ... frame, player B in the others. Both plan
each shot with the same budget, {budget:g} ms{"" if sims == 0 else f" (and at most {sims} simulations)"}; the planner sees
the table through the vision noise, and its first shot is played on the true table with
the execution noise (heading {first['noiseHeadingDeg']:g} deg, speed {100 * first['noiseSpeed']:g} %,
spins {first['noiseSpin']:g} rad/s) and simulated at full fidelity. The seed is {first['seed']}.

The players:

"""
    for name, what in PLAYERS.items():
        out += f"- `{name}`: {what};\n"
    if "breakValue" in first:
        out += (f"\n`default` and `one-ply` value keeping the table at {first['breakValue']:g} points beyond the "
                "potted ball's own (the request's break value, `snooker match --break-value`): in a frame a miss "
                "also hands the opponent the table. `direct-pots` keeps the planner's own 30, as it played when "
                "the targets were set, and so does self-play, where only the break's own points are to come "
                "([whole-frame-planner.md](whole-frame-planner.md) §10).\n")
    out += """
A stall is a turn whose plan offered no shot: the match then plays, for the player, a
firm straight shot at the nearest ball on (one with a clear path when there is one). For
`direct-pots` that shot is its own play when it has no direct pot, so its stalls count the
turns it had none. A break is the points of one visit that scored; the mean break is
over those. The share of decided frames comes with its 95 % Wilson interval: over a
hundred frames it is about ten points either way. Without a cap on simulations the
plans end on the clock, so a rerun on a loaded machine differs in its details.

## Targets

"""
    out += targets_table(runs, selfplay)
    out += direct_pots_section(runs)
    for opponent, vision, d, wall in runs:
        if opponent == "direct-pots" and vision == "0.2":
            out += stalls_paragraph(strokes.get((opponent, vision)), d)
            out += decided_section(strokes.get((opponent, vision)), d)
    out += noise_scan_section(runs, scan)
    out += lookahead_section(runs, selfplay)
    out += """
## All matches

"""
    out += summary_table(runs)
    for opponent, vision, d, wall in runs:
        out += f"\n## {d['playerA']} against {d['playerB']}, vision {vision} mm\n\n"
        out += player_table(d)
        out += (f"\nHighest break of the match {d['highestBreak']}, centuries {d['centuries']}; "
                f"frames ended level and sent to a re-spotted black {d['blackRespots']}; strokes the "
                f"simulator could not carry to rest (scored as fouls) {d['simulationFailures']}.\n")
    out += "\n## Planning time by kind of turn\n\n"
    out += timing_table(runs)
    out += "\n## Shot kinds and pot routes played\n\n"
    out += ("Strokes each player chose (stalls apart), by the kind its plan labelled them with, "
            "and its pots by route; fouls per stroke played. A kind the run's data does not "
            "count (it came later than the run) shows as -.\n\n")
    out += kinds_table(runs)
    if selfplay:
        out += "\n## Self-play\n\n"
        out += ("`snooker selfplay` (`planner/selfplay.h`): the planner plays breaks alone from seeded "
                "mid-frame tables (6 to 10 reds), asked for pots only (alone at the table there is no one "
                "to play safe against), at the same noise and budget.\n\n")
        out += selfplay_table(selfplay)
    out += f"\nMachine: {machine()}.\n"
    return out


def main(argv):
    if len(argv) >= 3 and argv[1] == "--handover":
        # Frames are numbered per log: each log's frames are kept apart.
        frames = []
        for path in argv[2:]:
            with (gzip.open(path, "rt") if path.endswith(".gz") else open(path)) as f:
                frames += frames_of([json.loads(line) for line in f if line.strip()])
        print(handover_table(handover_bins(frames), "B"), end="")
        print("\n" + returns_line(frames, "B"), end="")
        if any(s.get("planHandovers") is not None for frame in frames for s in frame):
            print("\n" + prediction_table(prediction_bins(frames), "A"), end="")
        return 0
    if len(argv) not in (4, 5):
        print(__doc__, file=sys.stderr)
        return 2
    data_dir, output, command = argv[1], argv[2], argv[3]
    revision = argv[4] if len(argv) == 5 else "?"
    runs = load(data_dir)
    if not runs:
        print(f"frame_play_report.py: no frame-play-*.json in {data_dir}", file=sys.stderr)
        return 1
    with open(output, "w") as f:
        strokes = {(o, v): load_strokes(data_dir, o, v) for o, v, _, _ in runs}
        f.write(document(runs, command, revision, load_selfplay(data_dir), strokes, load_noise_scan(data_dir)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
