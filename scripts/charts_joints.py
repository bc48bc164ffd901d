#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Turns rewind-joint-bench CSV into the 3D joint charts (gnuplot, SVG) and
the "3D joints" section of docs/BENCHMARKS.md.

Usage: scripts/charts_joints.py --csv joints3d.csv --run joints3d_run.txt
                                --out docs/charts --doc docs/BENCHMARKS.md

Called by scripts/charts.sh. Every figure of the section comes from the CSV
of one run; --run holds that run's mode, date and duration, so the section
can be rebuilt from the stored CSV after scripts/charts.py has rewritten the
rest of the document. The section sits between two marker comments and
replaces the previous one. Needs python3 (standard library) and gnuplot.
"""
import argparse
import csv
import os
import sys
from collections import OrderedDict

sys.dont_write_bytecode = True  # no scripts/__pycache__ from the import below
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from charts import gnuplot, machine, quote, splice_section  # noqa: E402  (shared with the 3D charts)

BEGIN = "<!-- joints3d:begin (scripts/charts_joints.py) -->"
END = "<!-- joints3d:end -->"

ENGINES = ("rewind", "bullet")
COLOURS = {"rewind": "#1f77b4", "bullet": "#d62728"}
FLOATS = ("ms_per_step", "max_opening_m", "final_opening_m", "max_stretch_pct",
          "final_stretch_pct", "period_s", "analytic_period_s", "period_error_pct",
          "energy_growth_pct", "energy_rebound_pct", "final_speed_mps")
INTS = ("size", "bodies", "joints", "default", "ticks", "loads", "loads_carried")

# The joint error charted for each scene, and the criterion the tests hold
# Rewind to (tests/stability/stability3d_joints.cpp,
# tests/accuracy/accuracy_joints3d.cpp, tests/stability/stability3d_ragdolls.cpp),
# drawn as a dashed line.
CHARTS = OrderedDict([
    ("pendulum", ("period_error_pct", "period error (%)", 0.5)),
    ("chain", ("max_stretch_pct", "largest stretch (% of 10 m)", 1.0)),
    ("bridge", ("max_opening_m", "widest joint opening (m)", 0.02)),
    ("grid", ("max_opening_m", "widest joint opening (m)", 0.05)),
    ("ragdoll_pile", ("max_opening_m", "widest joint opening (m)", 0.02)),
])

SCENE_TEXT = OrderedDict([
    ("pendulum", "a box rod (0.1 × 1 × 0.1 m, 10 kg, no damping) on a hinge about z at its end, "
                 "let go 0.05 rad from straight down; the period (from zero crossings over 10 s) "
                 "against the physical pendulum's 2π √(I_pivot / (m g d)) × (1 + a²/16)"),
    ("chain", "N box links (0.1 × 0.5 × 0.1 m, 5 kg) on ball joints, hanging straight down from "
              "a fixed point, holding a sphere (radius 0.3 m) of 100 times a link's mass; "
              "*stretch* is how much farther the sphere's anchor is from the pivot than the "
              "chain's 10 m"),
    ("bridge", "N planks (1 × 0.1 × 0.8 m, 48 kg, angular damping 0.5) hinged end to end about "
               "z and to two static posts, hung in a shallow V (0.2 rad), each hinge resisting "
               "with a friction torque of 100 N m (a motor at zero speed on both engines); 8 boxes "
               "of 0.5 m (125 kg) dropped from 1 to 3 m above the posts"),
    ("grid", "an N × N sheet of spheres (radius 0.15 m, 0.5 m apart, 14 kg) in the horizontal "
             "plane, each joined to its neighbours by a ball joint at their midpoint, the row at "
             "one edge static; the sheet falls from horizontal and swings about that edge"),
    ("ragdoll_pile", "N of Rewind's ragdolls (`rewind/sim/ragdoll3d.h` defaults: 1.8 m, 70 kg, "
                     "11 capsules, angular damping 0.5, friction 0.7; cone-twist waist, neck, "
                     "shoulders and hips, one-way hinges at elbows and knees) lying face up in "
                     "crossed layers of five, each turned a little, dropped from 0.4 to 4.5 m onto "
                     "a static floor, 8 s: the pile of `tests/stability/ragdoll_pile3d.h`, read "
                     "off the ragdoll builder. A ragdoll's parts do not collide with each other; "
                     "they do with other ragdolls and the floor. The widest opening of a pile is a "
                     "chaotic figure, one run's draw: on Rewind, moving one ragdoll 10 µm took "
                     "the stability suite's pile from 0.017 m to 0.11 m"),
])

MAPPING = """\
| Scene value | Rewind (3D lane, float32) | Bullet 3.24 (float, Debian's libbullet-dev, 1 thread) |
|---|---|---|
| description | `rewind/scenes/joint_scenes.h`: bodies (spheres, boxes, capsules along local y), joints with their anchors and axes in each body's frame | the same description (`bench/joint_engines.cpp`) |
| mass, inertia | from the density, Rewind's own shape mass | set from the description (the same box, sphere and capsule formulas) |
| capsule (ragdoll pile) | `Shape::make_capsule(r, h)` | `btCapsuleShape(r, 2 h)` |
| ball joint | `JointType::kBall` | `btPoint2PointConstraint` |
| hinge | `JointType::kHinge` | `btHingeConstraint` (one-body constructor for a joint to the world) |
| hinge friction (bridge) | hinge motor at speed 0, `max_motor_torque` = T | `enableAngularMotor(true, 0, T dt)` |
| ball joint with limits (ragdoll pile) | `kBall` with `enable_limit`: cone about axis_a, twist about axis_b in [lower, upper] | `btConeTwistConstraint` on the same frames, both swing spans the cone, twist span half the range (B's frame turned by its middle: Bullet's twist limit is symmetric) |
| hinge with limits (ragdoll pile) | `kHinge` with `enable_limit`, [lower, upper] | `btHingeConstraint` on the same frames, `setLimit(−upper, −lower)` (Bullet counts the angle the other way) |
| joined bodies | do not collide (`disable_collision`, the default) | do not collide (`addConstraint(c, true)`) |
| one ragdoll's parts | do not collide (a layer pair of their own, masked out) | do not collide (an overlap filter callback on a group index) |
| friction of a contact | √(f_a f_b) | f_a f_b (Bullet's rule; the coefficients are the same) |
| damping | angular damping as described (divides by 1 + d h) | `m_angularDamping` (multiplies by (1 − d)^dt) |
| step | `WorldConfig{}` (4 substeps, relax 1; 2 and 8 also run) | `stepSimulation(1/60, 1, 1/60)`, 10 iterations (Bullet's default; 20 and 40 also run), joint ERP 0.2, CFM 0 |
| sleeping | off | off (`DISABLE_DEACTIVATION`) |
| gravity, tick | (0, −9.81, 0) m/s², 60 Hz | the same |
"""


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in INTS:
            r[k] = int(float(r[k])) if r.get(k) not in (None, "") else None
        for k in FLOATS:
            r[k] = float(r[k]) if r.get(k) not in (None, "") else None
    return rows


def read_run(path):
    run = {}
    with open(path) as f:
        for line in f:
            if "=" in line:
                k, v = line.rstrip("\n").split("=", 1)
                run[k] = v
    return run


def pick(rows, engine):
    for r in rows:
        if r["engine"] == engine and r["default"]:
            return r
    return None


def short(r):
    label = r["settings"].replace("substeps=", "s").replace("iterations=", "i")
    return label + (" (default)" if r["default"] else "")


def num(v, digits=4):
    if v is None:
        return "–"
    if v != 0 and abs(v) < 10 ** -digits:
        return "%.2g" % v
    return "%.*f" % (digits, v)


def error_chart(out_dir, scene, size, metric, label, limit, rows):
    """One point per setting, joint error against ms/step, both engines."""
    name = "joints3d_%s_%d_%s" % (scene, size, metric)
    data_path = os.path.join(out_dir, name + ".dat")
    index = OrderedDict()
    with open(data_path, "w") as f:
        for engine in ENGINES:
            pts = sorted((r for r in rows if r["engine"] == engine and r[metric] is not None),
                         key=lambda r: r["ms_per_step"])
            if not pts:
                continue
            index[engine] = len(index)
            f.write("# %s\n" % engine)
            for r in pts:
                # A log axis cannot show 0: an exact zero sits at 1e-6.
                f.write("%g %g %s\n" % (r["ms_per_step"], max(r[metric], 1e-6), quote(short(r))))
            f.write("\n\n")
    values = [max(r[metric], 1e-6) for r in rows if r[metric] is not None] + [limit]
    logy = max(values) / min(values) > 20
    plots = []
    for engine, i in index.items():
        plots.append("%s index %d using 1:2 with points pt 7 ps 0.9 lc rgb %s title %s"
                     % (quote(data_path), i, quote(COLOURS[engine]), quote(engine)))
        plots.append("%s index %d using 1:2:3 with labels offset 0.6,0.5 left font ',8' "
                     "tc rgb %s notitle" % (quote(data_path), i, quote(COLOURS[engine])))
    plots.append("%g with lines dt 2 lc rgb 'gray40' title 'test criterion'" % limit)
    svg = os.path.join(out_dir, name + ".svg")
    gnuplot("\n".join([
        "set terminal svg size 720,440 dynamic noenhanced font 'sans,11' background rgb 'white'",
        "set output %s" % quote(svg),
        "set title %s" % quote("3D joints, %s %d: %s against cost (60 Hz, 1 thread, no sleeping)"
                               % (scene, size, label)),
        "set xlabel 'ms per step'",
        "set ylabel %s" % quote(label),
        "set logscale x",
        "set logscale y" if logy else "unset logscale y",
        "set grid",
        "set key top right",
        "plot " + ", \\\n  ".join(plots),
    ]) + "\n")
    os.remove(data_path)  # gnuplot input, rebuilt from the CSV
    return os.path.basename(svg)


def section(rows, run, rel_out, out_dir):
    d = []
    w = d.append
    w(BEGIN)
    w("## 3D joints: Rewind and Bullet on the same jointed scenes\n")
    w("Generated by `bash scripts/charts.sh%s` (`--only joints` regenerates this section alone) "
      "on %s in %s s (runs and charts; building not counted). Machine: %s. "
      "`build/bench/bin/rewind-joint-bench` builds each scene of "
      "`rewind/scenes/joint_scenes.h` on both engines and steps them in one process, taking "
      "turns in blocks of 10 ticks, so the load of a shared machine falls on both alike: "
      "compare the ratios, not the absolute figures, and only within one run. **Sleeping is "
      "off in both.** ms/step is the mean wall time of the engine's step over the scene's "
      "ticks (no warm-up: the scenes are measured from the moment they are let go).\n"
      % (" --quick" if run.get("mode") == "quick" else "", run.get("date", "?"),
         run.get("seconds", "?"), machine()))
    w("Every joint error is measured the same way on both engines, from the poses each reports: "
      "a joint's *opening* is the world distance between its two anchors (each body's pose "
      "applied to the anchor it was given); the chain's *stretch* how much farther its heavy "
      "sphere's anchor is from the pivot than the chain's length; the pendulum's *period error* "
      "its period from zero crossings against the analytic one. The grid's *energy growth* is "
      "how far kinetic plus potential energy ever rose above its start, *rebound* the largest "
      "rise above the lowest it had been (energy the joints took into their stretch when the "
      "sheet snapped taut and gave back), both in % of the energy the fall can release "
      "(m g L / 2). *Carried* counts the bridge's boxes still on its deck at the end.\n")

    w("### Default settings\n")
    w("| scene | size | bodies | joints | engine | settings | ms/step | widest opening (m) "
      "| opening at the end (m) | largest stretch (%) | stretch at the end (%) | period error (%) "
      "| energy growth / rebound (%) | carried | fastest at the end (m/s) |")
    w("|---|---:|---:|---:|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|")
    ratios = []
    for scene in SCENE_TEXT:
        srows = [r for r in rows if r["scene"] == scene]
        rw, bt = pick(srows, "rewind"), pick(srows, "bullet")
        for r in (rw, bt):
            if r is None:
                continue
            energy = "–"
            if r["energy_growth_pct"] is not None:
                energy = "%s / %s" % (num(r["energy_growth_pct"], 3),
                                      num(r["energy_rebound_pct"], 3))
            carried = "–" if r["loads"] is None else "%d of %d" % (r["loads_carried"], r["loads"])
            w("| %s | %d | %d | %d | %s | %s | %.3f | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                scene, r["size"], r["bodies"], r["joints"], r["engine"], r["settings"],
                r["ms_per_step"], num(r["max_opening_m"]), num(r["final_opening_m"]),
                num(r["max_stretch_pct"], 2), num(r["final_stretch_pct"], 2),
                num(r["period_error_pct"], 4), energy, carried, num(r["final_speed_mps"], 3)))
        if rw and bt and bt["ms_per_step"] > 0:
            ratios.append((scene, rw["ms_per_step"] / bt["ms_per_step"]))
    w("")
    if ratios:
        w("Rewind ms/step ÷ Bullet ms/step at default settings in this run: "
          + ", ".join("%s %.2f" % (s, v) for s, v in ratios) + ".\n")

    sweep = [r for r in rows if not r["default"]]
    if sweep:
        w("### Joint error against cost\n")
        w("Each point is one setting: Rewind's substeps (s4, s8, s16; relax 1) and Bullet's solver "
          "iterations (i10, i20, i40). The dashed line is the criterion Rewind's tests hold it to "
          "at default settings (`tests/stability/stability3d_joints.cpp`, "
          "`tests/accuracy/accuracy_joints3d.cpp`, `tests/stability/stability3d_ragdolls.cpp`, "
          "which steps the ragdoll pile with sleeping on).\n")
        for scene, (metric, label, limit) in CHARTS.items():
            srows = [r for r in rows if r["scene"] == scene]
            if len(srows) < 3:
                continue
            svg = error_chart(out_dir, scene, srows[0]["size"], metric, label, limit, srows)
            print("charts_joints: %s" % svg, file=sys.stderr)
            w("#### %s %d: %s\n" % (scene, srows[0]["size"], label))
            w("![3D joints %s %s](%s/%s)\n" % (scene, metric, rel_out, svg))
        w("| scene | engine | settings | ms/step | widest opening (m) | largest stretch (%) "
          "| period error (%) | carried |")
        w("|---|---|---|---:|---:|---:|---:|---:|")
        for r in rows:
            carried = "–" if r["loads"] is None else "%d of %d" % (r["loads_carried"], r["loads"])
            w("| %s | %s | %s%s | %.3f | %s | %s | %s | %s |" % (
                r["scene"], r["engine"], r["settings"], " (default)" if r["default"] else "",
                r["ms_per_step"], num(r["max_opening_m"]), num(r["max_stretch_pct"], 2),
                num(r["period_error_pct"], 4), carried))
        w("")

    w("### Joint scenes\n")
    w("| scene | what |")
    w("|---|---|")
    for k, v in SCENE_TEXT.items():
        w("| %s | %s |" % (k, v))
    w("")
    w("### Joint parameter mapping\n")
    w(MAPPING)
    w("### Reproducing the 3D joints section\n")
    w("```")
    w("bash scripts/charts.sh --only joints        # this section and its charts alone")
    w("build/bench/bin/rewind-joint-bench --help")
    w("build/bench/bin/rewind_joint_scene_bench    # Google Benchmark: the same scenes, one engine at a time")
    w("```")
    w("The CSV behind every table and chart of this section is `%s/joints3d.csv`." % rel_out)
    w(END)
    return "\n".join(d) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", required=True, help="rewind-joint-bench output")
    ap.add_argument("--run", required=True, help="key=value lines: mode, date, seconds")
    ap.add_argument("--out", required=True)
    ap.add_argument("--doc", required=True)
    args = ap.parse_args()
    rows = read_rows(args.csv)
    run = read_run(args.run)
    os.makedirs(args.out, exist_ok=True)
    doc_dir = os.path.dirname(os.path.abspath(args.doc))
    rel_out = os.path.relpath(os.path.abspath(args.out), doc_dir)
    # Before the 2D section when there is no joints section yet.
    splice_section(args.doc, section(rows, run, rel_out, args.out), BEGIN, END,
                   before="<!-- 2d:begin")
    print("charts_joints: wrote the 3D joints section of %s" % args.doc, file=sys.stderr)


if __name__ == "__main__":
    main()
