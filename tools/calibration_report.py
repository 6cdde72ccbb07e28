#!/usr/bin/env python3
"""Writes docs/calibration.md from the measurements of scripts/calibration-report:
the throw law fitted to Alciatore's data and its predictions at other cuts, the
paper's measured columns under the fitted law, the cushion fit, the identification
fits, the fit from tracked shots and the sim-to-real self-play table.

usage: calibration_report.py SNOOKER DATA_DIR OUT_MD COMMAND COMMIT
DATA_DIR holds the JSON the script wrote (docs/data/calibration-*.json,
sim-to-real-*.json).
"""
import json
import math
import os
import subprocess
import sys

from report_machine import machine

R = 0.02625
# Mathavan, Jackson & Parkin (2014), Tables 1 and 2: rolling cue ball, V0 (m/s), cut
# (deg), measured v_S (m/s) and exit angles (deg) after the slip, cue then object.
PAPER = [
    (1.539, 33.83, 0.816, 0.836, 35.96, 33.83),
    (1.032, 26.36, 0.520, 0.629, 33.20, 26.36),
    (1.364, 40.52, 0.925, 0.700, 30.50, 40.51),
    (1.731, 46.50, 1.275, 0.787, 27.97, 46.50),
    (0.942, 18.05, 0.365, 0.581, 29.86, 18.05),
]
# Alciatore's 30 deg stun curve, the two ends quoted with the 45 deg data: about
# 6.0 deg at the slow end and 3.5 deg at the fast end of the same speed range.
MEASURED_30 = [(0.35, 6.0), (1.75, 3.5)]


def load(data, name):
    with open(os.path.join(data, name)) as f:
        return json.load(f)


def collide(snooker, model, v0, cut):
    args = [snooker, "collide", "--speed", str(v0), "--topspin", str(v0 / R), "--cut-deg", str(cut), "--json"]
    if model:
        args += ["--model", model]
    out = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
    return (out["cue"]["slipEnd"]["speed"], out["object"]["slipEnd"]["speed"],
            out["cue"]["slipEnd"]["exitAngleDeg"], out["object"]["slipEnd"]["exitAngleDeg"])


def f(x, d=2):
    return "-" if x is None else f"{x:.{d}f}"


def law_of(fit):
    law = {p["name"]: p for p in fit["parameters"]}
    return tuple(law[n] for n in ("ball_ball.mu_bb", "ball_ball.slip_gain", "ball_ball.slip_decay"))


def law_text(fit, s):
    a, b, c = law_of(fit)
    return (f"mu = a + b exp(-c {s}): a = {a['value']:.4f} +- {a['uncertainty']:.3f}"
            f"{' (at its bound 0)' if a.get('atBound') else ''}, b = {b['value']:.4f} +- {b['uncertainty']:.3f}, "
            f"c = {c['value']:.3f} +- {c['uncertainty']:.2f} s/m")


def ends_30(pred):
    grid30 = {g["speed"]: g["fitted"] for g in pred["grid"] if g["cut"] == 30}
    errs = [abs(grid30[v] - t) for v, t in MEASURED_30 if v in grid30]
    text = ", ".join(f"{grid30[v]:.2f} deg at {v:g} m/s (measured {t:.1f})" for v, t in MEASURED_30 if v in grid30)
    return text, (sum(errs) / len(errs) if errs else float("nan"))


def cuts_table(pred, title):
    speeds = sorted({g["speed"] for g in pred["grid"]})
    out = ["", title, "", "| cut | " + " | ".join(f"{v:g}" for v in speeds) + " |", "|---|" + "---|" * len(speeds)]
    for cut in (20, 30, 45, 60):
        row = {g["speed"]: g for g in pred["grid"] if g["cut"] == cut}
        out.append(f"| {cut} deg | " + " | ".join(f"{row[v]['fitted']:.2f}" for v in speeds) + " |")
    return out


def throw_section(data):
    fit = load(data, "calibration-throw-fit.json")
    pred = load(data, "calibration-throw.json")
    fit_i = load(data, "calibration-throw-impact-fit.json")
    pred_i = load(data, "calibration-throw-impact.json")
    res = {r["kind"]: r for r in fit["residuals"]}["throw"]
    res_i = {r["kind"]: r for r in fit_i["residuals"]}["throw"]
    pts = pred["points"]
    pts_i = {p["speed"]: p["fitted"] for p in pred_i["points"]}
    rms_default = math.sqrt(sum((p["default"] - p["measured"]) ** 2 for p in pts) / len(pts))
    out = ["## Throw: the friction law fitted to measured throw", "",
           "Data: stun shots at a 45 deg cut, the object ball's speed against its throw, digitised from "
           "D. Alciatore, \"Throw Follow-up Part II: More Results\", Billiards Digest, August 2014 "
           "(`docs/data/throw-alciatore-45.json`). They were measured with phenolic pool balls; snooker balls "
           "are the same material, and the fit assumes the contact behaves the same (the balls' size and mass "
           "are the model's own).", "",
           "The law mu = a + b exp(-c s) comes in two forms (`physics/core/params.h`), and both are fitted:", "",
           "- **slip form** (`EXPONENTIAL`, Marlow's): s is the slip speed at the contact, evaluated along the "
           "impulse integration as the slip changes. `snooker calibrate --data docs/data/throw-alciatore-45.json "
           "--fit ball-ball` (the fit starts from Marlow's law, the family's one published member with a slope): "
           + law_text(fit, "s") + ".",
           "- **impact-speed form** (`EXPONENTIAL_IMPACT_SPEED`): s is the normal approach speed at first "
           "contact, one coefficient for the whole impact, lower the harder the balls meet (friction falling with "
           "the contact's load). The same command with `--model docs/data/impact-speed-law.json`, a model file "
           "that only chooses this form: " + law_text(fit_i, "v_n") + ".",
           "",
           "On a stun shot at 45 deg the slip and normal speeds are equal at first contact, so the 45 deg data "
           "cannot tell the forms apart; both fit them about as well. Eight points fix each curve's shape better "
           "than its three numbers apart: the uncertainties are large and strongly correlated.", "",
           f"Residuals (rms): the default constant law {rms_default:.2f} deg (it throws 2.86 deg at every "
           f"speed), Marlow's law {res['rmsBefore']:.2f} deg, the slip form {res['rmsAfter']:.2f} deg, the "
           f"impact-speed form {res_i['rmsAfter']:.2f} deg.", "",
           "| object-ball speed (m/s) | measured (deg) | default model | slip form | residual | impact-speed form "
           "| residual |", "|---|---|---|---|---|---|---|"]
    for p in pts:
        i = pts_i[p["speed"]]
        out.append(f"| {p['speed']:.2f} | {p['measured']:.2f} | {p['default']:.2f} | {p['fitted']:.2f} | "
                   f"{p['fitted'] - p['measured']:+.2f} | {i:.2f} | {i - p['measured']:+.2f} |")
    out += ["", "### At other cuts", "",
            "Each form's throw (deg) across the object ball's speed (m/s) for a stun shot. The default model "
            "throws 2.86 deg at every cut and speed."]
    out += cuts_table(pred, "Slip form:")
    out += cuts_table(pred_i, "Impact-speed form:")
    limits = {g["cut"]: g["limit"] for g in pred["gear_limit"]}
    text, err = ends_30(pred)
    text_i, err_i = ends_30(pred_i)
    out += ["", "Against the measured 30 deg curve (its ends, about 6.0 deg slow and 3.5 deg fast, taken at the "
            "45 deg data's slowest and fastest speeds):", "",
            f"- slip form: {text}, a mean error of **{err:.2f} deg**;",
            f"- impact-speed form: {text_i}, a mean error of **{err_i:.2f} deg**.", "",
            "The target of 1 deg on average is " + ("met by the impact-speed form" if err_i <= 1 else "**not met**")
            + (", not by the slip form." if err > 1 else (" and by the slip form." if err <= 1 else ".")),
            "",
            "Why the forms part at 30 deg: at 20 and 30 deg a stun contact can stop slipping during the impact, "
            "and its throw is then the geared limit tan(throw) = 2 tan(cut) / (7 (1 + e)), "
            + ", ".join(f"{limits[k]:.2f} deg at {k} deg" for k in (20, 30)) +
            " with e = 0.89, whatever the friction. In the slip form the coefficient rises as the slip dies away, "
            "so the contact sticks at 30 deg up to 2 m/s and the fast end stays at the limit. In the impact-speed "
            "form a fast impact keeps its low coefficient, keeps slipping, and throws like a 45 deg shot of the "
            "same object-ball speed, as the measurements do (3.5 deg at 30 deg, 3.0 at 45). Neither form reaches "
            "the slow end's 6 deg: above the geared limit, it needs a lower restitution (about 0.6) or a contact "
            "that is not rigid, neither of which the paper's measured e or its model allows.", "",
            "The sim-to-real world below uses the slip form (`calibration::SimToRealWorld`); both forms are "
            "fits of the same data, and the tracked-shot fit recovers whichever law the world has.", "",
            "The fitted law changes plans the way it should: with more throw the planner cuts thinner "
            "(`ModelPlanningTest.WithMoreThrowThePlannerCutsThinnerAndItsShotPotsInItsModel`: a 30 deg "
            "stun pot is cut 31.6 deg with the default model and 33.4 deg with a model that throws more)."]
    return out


def paper_section(snooker, data):
    models = (("default", None), ("slip", os.path.join(data, "calibration-throw-model.json")),
              ("impact", os.path.join(data, "calibration-throw-impact-model.json")))
    out = ["", "### The paper's measured columns under the fitted laws", "",
           "Tables 1 and 2 of Mathavan et al. (2014): rolling cue balls, each ball's speed v_S and exit angle "
           "after its slip on the cloth, against the measurements (`snooker collide --model "
           "docs/data/calibration-throw-model.json`, and `calibration-throw-impact-model.json` for the "
           "impact-speed form). Each cell gives the default model / the slip form / the impact-speed form. The "
           "object ball's measured exit angle equals the cut in every row: the paper took its cut angles from "
           "the object ball's path, so those columns carry no throw. The cue ball's columns do depend on the "
           "friction law.", "",
           "| V0 (m/s) | cut (deg) | cue v_S measured | model | cue exit measured | model | object v_S measured "
           "| model |", "|---|---|---|---|---|---|---|---|"]
    err = {name: [] for name, _ in models}
    for v0, cut, cs, os_, ce, _ in PAPER:
        got = {name: collide(snooker, path, v0, cut) for name, path in models}
        for name, p in got.items():
            err[name].append((abs(p[0] - cs) / cs, abs(p[2] - ce) / ce, abs(p[1] - os_) / os_))
        def cells(k, d):
            return " / ".join(f"{got[name][k]:.{d}f}" for name, _ in models)
        out.append(f"| {v0} | {cut} | {cs:.3f} | {cells(0, 3)} | {ce:.2f} | {cells(2, 2)} | {os_:.3f} | "
                   f"{cells(1, 3)} |")
    def mean(k):
        return " / ".join(f"{100 * sum(e[k] for e in err[name]) / len(err[name]):.1f}" for name, _ in models)
    out += ["", f"Mean |error| against the measurements, default / slip form / impact-speed form: cue v_S "
            f"{mean(0)} %, cue exit angle {mean(1)} %, object v_S {mean(2)} %."]
    return out


def cushion_section(data):
    d = load(data, "calibration-cushion.json")
    fit = d["fit"]
    last = d["rebounds"][-1]
    out = ["", "## Cushion: the restitution curve on this table's nose", "",
           "The default restitution curve was fitted (docs/cushion-model.md) for a 36.75 mm nose; the table "
           "simulates a 36 mm one (TableSpec::cushion_height). Data: the measured rebound fit of Mathavan et al. "
           "(2009), v_out = -0.0877 v^2 + 1.131 v - 0.0953, rolling balls square on, sampled every 0.2 m/s from "
           "0.3 to 3.5 m/s (`calibration_report cushion`; the group fits the nose friction mu_w and each "
           "restitution knot at least two rebounds cover). Residual rms "
           f"{fit['rebound_speed']['before']:.4f} m/s with the default curve, {fit['rebound_speed']['after']:.4f} "
           f"after; at 3.5 m/s the default is {last['default'] - last['measured']:+.3f} m/s off the measured fit, "
           f"the fitted curve {last['fitted'] - last['measured']:+.4f}.", "",
           "| knot (m/s) | default e | fitted e |", "|---|---|---|"]
    fitted_names = {p["name"] for p in fit["parameters"]}
    for k, knot in enumerate(d["knots"]):
        mark = "" if f"cushion.restitution_curve.e[{k}]" in fitted_names else " (not covered: kept)"
        out.append(f"| {knot['speed']:g} | {knot['default']:.3f} | {knot['fitted']:.3f}{mark} |")
    mu = {p["name"]: p for p in fit["parameters"]}.get("cushion.mu_w")
    if mu:
        out += ["", f"mu_w: {mu['start']:.3f} -> {mu['fitted']:.3f} +- {mu['sigma']:.3f} (square-on rebounds show "
                "the nose friction only weakly). Below 0.3 m/s there is still no measurement: the lowest knot "
                "holds, as before. The default model is unchanged; a table that wants the refitted curve takes it "
                "from a model file."]
    return out


def identify_section(data):
    rows = load(data, "calibration-identify.json")
    out = ["", "## Identification: data made with known parameters, fitted back", "",
           "Each row: a world unlike the default, data simulated in it with noise, the group fitted from the "
           "default model (`calibration_report identify`; the unit tests `Groups/Identifiability.*` check the "
           "same on smaller sets). Tracked shots: random scenes of the cue ball and one or two object balls, "
           "strikes in the cue's terms, positions every 0.1 s (`snooker record`).", "",
           "| group | data | parameter | true | fitted | +- sigma | error / sigma |", "|---|---|---|---|---|---|---|"]
    for r in rows:
        fit = r["fit"]
        if fit["error"]:
            out.append(f"| {r['group']} | {r['data']} | refused: {fit['error']} | | | | |")
            continue
        for p in fit["parameters"]:
            t = r["truth"].get(p["name"])
            z = abs(p["fitted"] - t) / p["sigma"] if t is not None and p["sigma"] else float("nan")
            out.append(f"| {r['group']} | {r['data']} | {p['name']} | {t:g} | {p['fitted']:.6g} | "
                       f"{p['sigma']:.2g} | {z:.1f} |")
    out += ["", "Every value comes back within a few parts in a thousand. The stated uncertainties (linearised, "
            "from the Jacobian at the optimum) are right for throws and rebounds; for tracked shots they can "
            "understate the error several-fold: the positions after a collision are strongly non-linear in the "
            "parameters. The starting positions of a tracked shot are taken as known: a robot sees the resting "
            "balls over many frames before it strikes. With 1 mm of noise on them as well, a collision turns it "
            "into centimetres and the ball-ball and cue fits miss (the cloth still comes back)."]
    return out


def tracked_section(data):
    fit = load(data, "calibration-tracked-fit.json")
    world = load(data, "sim-to-real-world.json")
    truth = {"ball_ball.mu_bb": world["ballBall"]["muBb"], "ball_ball.slip_gain": world["ballBall"]["slipGain"],
             "ball_ball.slip_decay": world["ballBall"]["slipDecay"], "cloth.mu_s": world["cloth"]["muS"],
             "cloth.mu_r": world["cloth"]["muR"], "cloth.spin_decel": 22.0, "cue.end_mass": world["cue"]["endMassKg"],
             "cue.tip_restitution": 0.73}
    res = {r["kind"]: r for r in fit["residuals"]}["tracked"]
    out = ["", "## Cloth, ball-ball and cue from 200 tracked shots", "",
           "The sim-to-real world below, 200 shots recorded in it with 1 mm of vision noise and fitted together "
           "(`snooker record --world docs/data/sim-to-real-world.json --shots 200 --seed 1 --vision-noise-mm 1 "
           "--out T.json`, then `snooker calibrate --data T.json --fit ball-ball,cloth,cue --out "
           "docs/data/sim-to-real-fitted-model.json`): "
           f"{res['count']} position residuals, rms {1000 * res['rmsBefore']:.0f} mm from the default model, "
           f"{1000 * res['rmsAfter']:.2f} mm after (the noise is 1 mm), {fit['evaluations']} model evaluations.", "",
           "| parameter | default | world | fitted | +- sigma |", "|---|---|---|---|---|"]
    for p in fit["parameters"]:
        out.append(f"| {p['name']} | {p['start']:g} | {truth.get(p['name'], float('nan')):.6g} | {p['value']:.6g} | "
                   f"{p['uncertainty']:.2g} |")
    return out


def selfplay_section(data, frames_note):
    names = [("calibration-selfplay-default.json", "the default model", "the default model (matched)"),
             ("calibration-selfplay-world-default-model.json", "the world", "the default model"),
             ("calibration-selfplay-world-matched.json", "the world", "the world's own model (matched)"),
             ("calibration-selfplay-world-fitted.json", "the world", "fitted from 200 tracked shots")]
    runs = []
    for file, world, model in names:
        path = os.path.join(data, file)
        if os.path.exists(path):
            runs.append((world, model, load(data, file)))
    w = load(data, "sim-to-real-world.json")
    if not frames_note and runs:
        frames_note = (f"{runs[0][2]['frames']} frames each, seed 1 (saved runs in docs/data/calibration-selfplay-*.json; "
                       f"`FRAMES={runs[0][2]['frames']} scripts/calibration-report` measures them again).")
    out = ["", "## Sim-to-real: the planner on a table unlike its model", "",
           "The world: the throw law fitted above (mu = "
           f"{w['ballBall']['muBb']:.3g} + {w['ballBall']['slipGain']:.4f} exp(-{w['ballBall']['slipDecay']:.4f} s)), "
           f"the cloth 20 % slower (mu_s {w['cloth']['muS']:.3f}, mu_r {w['cloth']['muR']:.5f}) and a stiffer "
           f"shaft (end mass {1000 * w['cue']['endMassKg']:.0f} g against 6 g: more squirt) "
           "(`docs/data/sim-to-real-world.json`). Self-play (`snooker selfplay --frames N --seed 1 --budget-ms 2000 "
           "--max-simulations 4800 [--model M] [--world W]`: the default budget's 4800 simulations as a cap that "
           "binds first, so that every model gets the same work and the frames are the same on any machine): the "
           "planner plans with its model, the strokes, with the cue's default noise, are played in the world. "
           f"Planning times are those of the measuring run, on a machine shared with other work. {frames_note}", "",
           "| world | planner's model | frames | shots | pot rate | mean break | plan p50 / p99 (ms) |",
           "|---|---|---|---|---|---|---|"]
    for world, model, r in runs:
        out.append(f"| {world} | {model} | {r['frames']} | {r['shots']} | {100 * r['potRate']:.1f} % | "
                   f"{r['meanBreak']:.1f} | {r['planMsP50']:.0f} / {r['planMsP99']:.0f} |")
    if len(runs) == 4:
        d, m, f_ = runs[1][2], runs[2][2], runs[3][2]
        gap = 100 * (f_["potRate"] - m["potRate"])
        out += ["", f"On the world, the default model drops {100 * (m['potRate'] - d['potRate']):.1f} points of pot rate "
                f"and {m['meanBreak'] - d['meanBreak']:.1f} of mean break against its own model; the fitted model "
                f"is {gap:+.1f} points from the matched one (target: within 1), "
                + ("**met**." if abs(gap) <= 1 else "**not met**.")]
    return out


def main():
    snooker, data, out_md, command, commit = sys.argv[1:6]
    frames_note = os.environ.get("FRAMES_NOTE", "")
    lines = ["# Calibration: the model fitted to a table", "",
             f"Generated by `{command}` at commit {commit} on {machine()} (do not edit by hand). The fits are "
             "`snooker calibrate` (calibration/fit.h: bounded least squares with NLopt's BOBYQA, derivative-free "
             "because tracked positions come out of an event-driven simulation whose outputs kink at events; each "
             "parameter's uncertainty from the residual Jacobian at the optimum). Data files and answers: "
             "`docs/data/calibration-*.json`, `docs/data/sim-to-real-*.json`.", ""]
    lines += throw_section(data)
    lines += paper_section(snooker, data)
    lines += cushion_section(data)
    lines += identify_section(data)
    lines += tracked_section(data)
    lines += selfplay_section(data, frames_note)
    lines += ["", "## Defaults", "",
              "The default model stays the default: nothing above changes it unless a model file is given "
              "(`--model FILE`; `ModelCommandTest.JsonReadsBackAsTheSameModelAndTheDefaultStaysTheDefault`, "
              "`ModelServerTest.ADefaultServerReportsTheDefaultModel`). A model whose friction law is not the "
              "constant one answers every ball-ball impact with the solver: the precomputed impact table is keyed "
              "to the constant law, so such a model's shots cost more (the planning times above)."]
    with open(out_md, "w") as f_:
        f_.write("\n".join(lines) + "\n")


if __name__ == "__main__":
    main()
