#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Turns rewind-scene2d-sweep CSV into the 2D charts (gnuplot, SVG) and the
2D section of docs/BENCHMARKS.md.

Usage: scripts/charts2d.py --csv 2d_sweep.csv --run 2d_run.txt --out docs/charts
                           --doc docs/BENCHMARKS.md

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

BEGIN = "<!-- 2d:begin (scripts/charts2d.py) -->"
END = "<!-- 2d:end -->"

# box2d3 (Box2D v3) rows exist only when the sweep was built with it
# (scripts/charts.sh --box2d3 DIR); without them the section is as before.
ENGINES = ("rewind", "box2d", "box2d3")
COLOURS = {"rewind": "#1f77b4", "box2d": "#2ca02c", "box2d3": "#d62728"}


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in ("size", "bodies", "default", "warmup_ticks", "timed_ticks", "escaped"):
            r[k] = int(r[k])
        for k in ("ms_per_step", "top_drift_m", "top_peak_m", "max_displacement_m",
                  "max_opening_m"):
            r[k] = float(r[k])
    return rows


def read_run(path):
    run = {}
    with open(path) as f:
        for line in f:
            if "=" in line:
                k, v = line.rstrip("\n").split("=", 1)
                run[k] = v
    return run


def short(r):
    """Chart label of a setting: s4 (Rewind or Box2D v3 substeps), v8p3 (Box2D 2.4
    iterations)."""
    kv = dict(p.split("=") for p in r["settings"].split())
    if r["engine"] == "box2d3":
        label = "s%s" % kv["substeps"]
    elif r["engine"] == "rewind":
        label = "s%s" % kv["substeps"] + ("" if kv["relax"] == "1" else ",r%s" % kv["relax"])
    else:
        label = "v%sp%s" % (kv["velocity"], kv["position"])
        if kv.get("continuous") == "0":
            label += ",no-ccd"
    return label + (" (default)" if r["default"] else "")


def error_chart(out_dir, scene, size, metric, label, rows):
    """One point per setting, error against ms/step, both engines."""
    name = "2d_%s_%d_%s" % (scene, size, metric)
    data_path = os.path.join(out_dir, name + ".dat")
    index = OrderedDict()
    with open(data_path, "w") as f:
        for engine in ENGINES:
            pts = sorted((r for r in rows if r["engine"] == engine), key=lambda r: r["ms_per_step"])
            if not pts:
                continue
            index[engine] = len(index)
            f.write("# %s\n" % engine)
            for r in pts:
                # A log axis cannot show 0: an exact zero sits at 1 µm.
                f.write("%g %g %s\n" % (r["ms_per_step"], max(r[metric], 1e-6), quote(short(r))))
            f.write("\n\n")
    values = [max(r[metric], 1e-6) for r in rows]
    logy = max(values) / min(values) > 10
    plots = []
    for engine, i in index.items():
        plots.append("%s index %d using 1:2 with points pt 7 ps 0.9 lc rgb %s title %s"
                     % (quote(data_path), i, quote(COLOURS[engine]), quote(engine)))
        plots.append("%s index %d using 1:2:3 with labels offset 0.6,0.5 left font ',8' "
                     "tc rgb %s notitle" % (quote(data_path), i, quote(COLOURS[engine])))
    svg = os.path.join(out_dir, name + ".svg")
    gnuplot("\n".join([
        "set terminal svg size 720,440 dynamic noenhanced font 'sans,11' background rgb 'white'",
        "set output %s" % quote(svg),
        "set title %s" % quote("2D %s %d: %s against cost (60 Hz, 1 thread, no sleeping)"
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


def pick(rows, engine, settings=None):
    for r in rows:
        if r["engine"] != engine:
            continue
        if settings is None and r["default"]:
            return r
        if settings is not None and r["settings"] == settings:
            return r
    return None


B2_FAST = "velocity=4 position=2"
B2_NO_CCD = "velocity=8 position=3 continuous=0"
STOOD_M = 2.0  # m: two box widths of the pyramids' boxes


def stood(r):
    return "yes" if r["max_displacement_m"] < STOOD_M else "no"

SCENE_TEXT = OrderedDict([
    ("large_pyramid", "a pyramid of base N (N (N + 1) / 2 boxes of half size 0.5 m, each row "
                      "shifted half a box, boxes touching side by side) on a static ground box"),
    ("pyramids", "N pyramids of base 10 (55 boxes each) side by side, 2 m apart, on one ground box"),
    ("tumbler", "a hollow 20 m box (four 1 m thick walls) turning at 0.05π rad/s about its centre, "
                "filled at once with N boxes of half size 0.125 m (a 0.5 m grid). Rewind: four "
                "kinematic bodies with offset boxes, their origins at the centre; Box2D: one "
                "kinematic body with four fixtures"),
    ("joint_grid", "an N × N grid of circles (radius 0.4 m, 1 m apart), each joined to its upper "
                   "and left neighbours by a revolute joint at their midpoint (2 N (N − 1) "
                   "joints), hanging from the 7 middle circles of the top row (static); joined "
                   "bodies do not collide"),
    ("smash", "no gravity: a box of half size 4 m (density 8) flying at 40 m/s into a wall of "
              "N × 80 boxes of half size 0.2 m, touching, that start asleep (each engine's "
              "asleep-at-creation flag) and wake as the blow reaches them; Box2D v3's smash "
              "benchmark"),
    ("rain", "Box2D v3's rain benchmark: 5 static floors 45 m apart, each 12.5 N + 1 boxes of 0.5 m (501 at N = 40, as Box2D's) "
             "(Rewind: one static body per box; Box2D: one body of many boxes); every 8 ticks a "
             "column of 5 groups of 5 ragdolls drops from 40 m above each floor. A ragdoll is "
             "11 capsules and 10 revolute joints with limits, a 5 Hz spring (damping ratio 0.5) "
             "and joint friction (a motor at speed 0), its shapes on collision layers so that "
             "ragdolls of the same number in their groups never touch, as Box2D's group "
             "indices do; its feet (a second shape on each lower leg in Box2D's ragdoll) are "
             "left out, as a Rewind 2D body has one shape. After N columns the oldest column "
             "is destroyed before each new one drops; the drops and removals count as step "
             "time, as in Box2D's benchmark. Box2D 2.4 sits out (its revolute joint has no "
             "spring)"),
])

MAPPING = """\
| Scene value | Rewind 2D lane (Q16.16 fixed point) | Box2D 2.4.1 (float, Debian's libbox2d-dev, 1 thread) |
|---|---|---|
| description | `bench/scene2d.h`: lengths, angles and speeds in thousandths; Rewind gets `Fx::ratio(v, 1000)` | the same integers ÷ 1000 as float |
| density, friction, restitution | 1 kg/m², 0.6, 0 | the same (fixture values; Box2D's default friction is 0.2) |
| friction combine | geometric mean √(μa μb) | Box2D's default b2MixFriction: √(μa μb) |
| gravity, tick | (0, −10) m/s² (none in the smash), 60 Hz | the same |
| step | `World2DConfig{}`: 4 soft-step substeps, 1 relax pass | `b2World::Step(1/60, 8, 3)` (Box2D's defaults); 4/2 also reported |
| sleeping | off (`World2DConfig::enable_sleep = false`); the smash's wall starts asleep (`BodyDef2D::awake = false`) and wakes when touched | off (`b2World::SetAllowSleeping(false)`; the smash's wall `b2BodyDef::awake = false`), so both engines do the same work |
| skin, slop | exact boxes; speculative contacts from 2 cm; slop 5 mm | polygons carry a 1 cm skin (b2_polygonRadius), so touching boxes start 2 cm inside each other's skin and push apart; slop 5 mm |
| penetration recovery | soft contacts (contact_hertz 30, damping ratio 10), push-out capped at 3 m/s | Baumgarte position iterations (0.2, at most 0.2 m per step) |
| fast bodies | speculative contacts; continuous collision only for bodies that opt in (`BodyDef2D::continuous`, none here) | Box2D's default continuous collision of dynamic against static/kinematic bodies |
| kinematic pivot | each body turns about its origin | the same |
| joints | revolute `JointDef2D` (anchor given twice), solved in the substeps beside the contacts; the rain's with `enable_limit`, `enable_spring` (`hertz`, `damping_ratio`), a motor at speed 0 as friction (`max_motor`) and `reference_angle` | `b2RevoluteJointDef::Initialize`, velocity and position iterations as above (no rain: 2.4.1's revolute joint has no spring) |
| ragdolls (rain) | `make_capsule`, friction 0.2, `BodyDef2D::layer` and `mask`, `linear_damping` as given | – |
"""


MAPPING_V3 = """\
| Scene value | Box2D %s (float, C, built from its source tree, 1 thread) |
|---|---|
| description, density, friction, restitution, gravity, tick | as Box2D 2.4 (shape material values; friction mixed as √(μa μb)) |
| step | `b2World_Step(1/60, 4)`: 4 soft-step substeps (Box2D v3's recommendation); 2 and 8 in the sweep |
| sleeping | off (`b2WorldDef::enableSleep = false`); the smash's wall `isAwake = false` with the body's `enableSleep` on (Box2D v3 makes a body that may not sleep awake) |
| skin, slop | exact boxes (polygon radius 0); speculative contacts; slop 5 mm |
| penetration recovery | soft contacts (contact_hertz 30, damping ratio 10), push-out capped at 3 m/s: Box2D v3's defaults |
| fast bodies | Box2D v3's default continuous collision of dynamic against static bodies |
| threads | one, the caller's (`workerCount` at its default, no task system) |
| joints | `b2RevoluteJointDef` with the anchor in each body's frame and their reference angle, as 2.4's `Initialize`, plus the scene's (the rain's lower arms); limits, spring (`enableSpring`, `hertz`, `dampingRatio`) and friction (`enableMotor`, `maxMotorTorque`) as given |
| ragdolls (rain) | capsules (`b2CreateCapsuleShape`), friction 0.2, category and mask bits as the scene's layers, `linearDamping` as given |
"""


def section(rows, run, rel_out, out_dir, rays=None):
    d = []
    w = d.append
    w(BEGIN)
    v3 = any(r["engine"] == "box2d3" for r in rows)
    v3_name = "Box2D " + run.get("box2d3", "v3")
    # A fixed anchor: the heading names the peers of the run, the links do not.
    w('<a id="2d-lane"></a>\n')
    if v3:
        w("## 2D lane: Rewind, Box2D 2.4 and %s on the same scenes\n" % v3_name)
    else:
        w("## 2D lane: Rewind and Box2D 2.4 on the same scenes\n")
    w("Generated by `bash scripts/charts.sh%s` (`--only 2d` regenerates this section alone) on %s "
      "in %s s "
      "(sweep and charts; building not counted). Machine: %s. Both engines step each scene in "
      "one process, taking turns in blocks of 10 ticks, so that the load of a shared machine "
      "falls on both alike: compare the ratios, not the absolute figures, and only within one run."
      "\n" % (" --quick" if run.get("mode") == "quick" else "", run.get("date", "?"),
              run.get("seconds", "?"), machine()))
    w("Every scene is built from one description (`bench/scene2d.h`) on both engines: the same "
      "sizes, densities (1 kg/m²), friction 0.6, restitution 0, gravity and 60 Hz ticks. Rewind "
      "runs `World2DConfig{}` (4 substeps, relax 1); Box2D 2.4.1 its defaults (8 velocity, 3 "
      "position iterations) and, as the cheaper setting, 4/2; 8/3 also runs with Box2D's "
      "continuous collision off (*no CCD*; Box2D's default is on, Rewind's speculative contacts "
      "are always on) to show that part of Box2D's step. **Sleeping is off in both**, so "
      "every body is simulated in both engines and they do the same work. "
      "ms/step is the mean wall time of the engine's step over the timed ticks, after a warm-up.\n")
    if v3:
        w("%s, an optional peer (`scripts/charts.sh --box2d3 DIR` builds it from a source tree), "
          "steps the same scenes in the same turns: its defaults (4 substeps, continuous "
          "collision on), one thread, sleeping off.\n" % v3_name)

    lp = [r for r in rows if r["scene"] == "large_pyramid"]
    rw, bx = pick(lp, "rewind"), pick(lp, "box2d")
    if rw and bx:
        ratio = rw["ms_per_step"] / bx["ms_per_step"]
        w("**Large pyramid (base %d, %s boxes), Rewind ms/step ÷ Box2D 2.4 ms/step in this run: "
          "%.2f** (target: within 1.5; %s).\n"
          % (rw["size"], format(rw["bodies"] - 1, ","), ratio,
             "met" if ratio <= 1.5 else "not met"))
        b3 = pick(lp, "box2d3")
        if b3:
            w("**Rewind ms/step ÷ %s ms/step on the same pyramid: %.2f.**\n"
              % (v3_name, rw["ms_per_step"] / b3["ms_per_step"]))

    w("### Cost, default settings\n")
    w("| scene | size | bodies | ticks (warm-up + timed) | Rewind ms/step | Box2D 8/3 ms/step "
      "| Rewind / Box2D 8/3 | Box2D 4/2 ms/step | Rewind / Box2D 4/2 | Box2D 8/3 no CCD ms/step "
      "| Rewind / Box2D 8/3 no CCD |" + (" Box2D v3 ms/step | Rewind / Box2D v3 |" if v3 else ""))
    w("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|" + ("---:|---:|" if v3 else ""))
    for scene in SCENE_TEXT:
        srows = [r for r in rows if r["scene"] == scene]
        rw, bx, fast = pick(srows, "rewind"), pick(srows, "box2d"), pick(srows, "box2d", B2_FAST)
        no_ccd = pick(srows, "box2d", B2_NO_CCD)
        others = (fast, no_ccd, pick(srows, "box2d3")) if v3 else (fast, no_ccd)
        if not rw:
            continue
        cells = [scene, str(rw["size"]), str(rw["bodies"]),
                 "%d + %d" % (rw["warmup_ticks"], rw["timed_ticks"]),
                 "%.2f" % rw["ms_per_step"]]
        cells += (["%.2f" % bx["ms_per_step"], "%.2f" % (rw["ms_per_step"] / bx["ms_per_step"])]
                  if bx else ["–", "–"])
        for other in others:
            if other:
                cells += ["%.2f" % other["ms_per_step"],
                          "%.2f" % (rw["ms_per_step"] / other["ms_per_step"])]
            else:
                cells += ["–", "–"]
        w("| " + " | ".join(cells) + " |")
    w("")

    w("### Accuracy and stability, default settings\n")
    w("Pyramids: *top drift* is how far the top box (the farthest of the tops, for many "
      "pyramids) ended from where it started; *top peak* the largest such distance at any "
      "timed tick (a tall pyramid sways and sinks under its load and Box2D's 1 cm skin pushes "
      "touching boxes apart, so the end pose alone can miss the extremes); *max displacement* "
      "the farthest any box ended from its start. A pyramid *stood* when no box ended %g m "
      "(two box widths) or more from its start; one that fell shows metres. Tumbler: boxes "
      "whose centre ended outside the container. Joint grid and rain: *widest opening*, the "
      "largest distance at the end between a joint's anchor as one of its bodies carries it "
      "and as the other does (0 for a joint that holds). Rain: *escaped* counts ragdoll "
      "parts that ended below the lowest floor. Smash: *max displacement*, how far the blow "
      "threw the farthest box of the wall.\n" % STOOD_M)
    w("| scene | size | engine | settings | top drift (m) | top peak (m) | max displacement (m) "
      "| stood | escaped | widest opening (m) |")
    w("|---|---:|---|---|---:|---:|---:|---|---:|---:|")
    for scene in SCENE_TEXT:
        srows = [r for r in rows if r["scene"] == scene]
        for r in (pick(srows, "rewind"), pick(srows, "box2d"), pick(srows, "box2d", B2_FAST),
                  pick(srows, "box2d", B2_NO_CCD), pick(srows, "box2d3")):
            if r is None:
                continue
            pyr = scene in ("large_pyramid", "pyramids")
            w("| %s | %d | %s | %s | %s | %s | %s | %s | %s | %s |" % (
                scene, r["size"], r["engine"], r["settings"],
                "%.4f" % r["top_drift_m"] if pyr else "–",
                "%.4f" % r["top_peak_m"] if pyr else "–",
                "%.4f" % r["max_displacement_m"] if pyr or scene == "smash" else "–",
                stood(r) if pyr else "–",
                str(r["escaped"]) if scene in ("tumbler", "rain") else "–",
                "%.4f" % r["max_opening_m"] if scene in ("joint_grid", "rain") else "–"))
    w("")

    w("### Error against cost\n")
    w("Each point is one setting: Rewind's substeps (s4, s6, s8, s16; relax 1; fewer than 4 at 60 Hz are refused) and Box2D's "
      "velocity iterations (v2, v4, v8, v16; position iterations 3), plus Box2D 4/2 (v4p2) and "
      "8/3 without continuous collision (no-ccd)%s. "
      "All settings of a scene ran in the same process, in turns.\n"
      % (", and Box2D v3's substeps (s2, s4, s8)" if v3 else ""))
    for scene in ("large_pyramid", "pyramids"):
        srows = [r for r in rows if r["scene"] == scene]
        if len(srows) <= 3:
            continue  # no sweep for this scene in this run
        size = srows[0]["size"]
        for metric, label in (("top_peak_m", "top box's largest drift (m)"),
                              ("max_displacement_m", "max displacement of any box (m)")):
            svg = error_chart(out_dir, scene, size, metric, label, srows)
            print("charts2d: %s" % svg, file=sys.stderr)
            w("#### %s %d: %s\n" % (scene, size, label))
            w("![2D %s %d %s](%s/%s)\n" % (scene, size, metric, rel_out, svg))
        w("| engine | settings | ms/step | top drift (m) | top peak (m) | max displacement (m) "
          "| stood |")
        w("|---|---|---:|---:|---:|---:|---|")
        for r in srows:
            w("| %s | %s%s | %.2f | %.4f | %.4f | %.4f | %s |" % (
                r["engine"], r["settings"], " (default)" if r["default"] else "",
                r["ms_per_step"], r["top_drift_m"], r["top_peak_m"], r["max_displacement_m"],
                stood(r)))
        w("")

    if rays:
        w("### Raycasts\n")
        w("Closest-hit rays per second in the large pyramid (5,050 boxes, as built: both engines "
          "answer for the same poses), %s rays from above and across, the engines taking turns in "
          "blocks of 1,000 (`build/bench/bin/rewind-rays2d`). *Agree* is the share of rays both "
          "engines answer alike: both miss, or both hit within 1 cm along the ray (Box2D's boxes "
          "carry a 1 cm skin).\n" % rays[0]["rays"])
        w("| engine | rays/s | hits | agree |")
        w("|---|---:|---:|---:|")
        for r in rays:
            w("| %s | %s | %s | %s%% |" % (r["engine"], "{:,}".format(int(r["rays_per_s"])),
                                          r["hits"], r["agree_pct"]))
        rw = [r for r in rays if r["engine"] == "rewind"]
        bx = [r for r in rays if r["engine"] == "box2d"]
        b3 = [r for r in rays if r["engine"] == "box2d3"]
        if rw and bx:
            w("\n**Rewind rays/s ÷ Box2D rays/s in this run: %.2f.**\n"
              % (float(rw[0]["rays_per_s"]) / float(bx[0]["rays_per_s"])))
        else:
            w("")
        if rw and b3:
            w("**Rewind rays/s ÷ %s rays/s in this run: %.2f** (a peer's *agree* compares it "
              "with Rewind; Rewind's, Rewind with Box2D 2.4).\n"
              % (v3_name, float(rw[0]["rays_per_s"]) / float(b3[0]["rays_per_s"])))

    w("### 2D scenes\n")
    w("| scene | what |")
    w("|---|---|")
    for k, v in SCENE_TEXT.items():
        w("| %s | %s |" % (k, v))
    w("")
    w("### 2D parameter mapping\n")
    w(MAPPING)
    if v3:
        w(MAPPING_V3 % run.get("box2d3", "v3"))
    w("### Reproducing the 2D section\n")
    w("```")
    w("bash scripts/charts.sh --only 2d           # this section and its charts alone")
    w("build/bench/bin/rewind-scene2d-sweep --help")
    w("build/bench/bin/rewind_scene2d_bench       # Google Benchmark: the same scenes, one engine at a time")
    w("build/bench/bin/rewind-rays2d [RAYS]       # raycasts per second, both engines")
    if v3:
        w("bash scripts/charts.sh --only 2d --box2d3 DIR   # with Box2D v3 from the source tree DIR")
    w("```")
    w("The CSV behind every 2D table and chart is `%s/2d_sweep.csv`." % rel_out)
    w(END)
    return "\n".join(d) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--csv", required=True, help="rewind-scene2d-sweep output")
    ap.add_argument("--run", required=True, help="key=value lines: mode, date, seconds")
    ap.add_argument("--out", required=True)
    ap.add_argument("--doc", required=True)
    ap.add_argument("--rays", help="rewind-rays2d output (optional)")
    args = ap.parse_args()
    rows = read_rows(args.csv)
    run = read_run(args.run)
    os.makedirs(args.out, exist_ok=True)
    doc_dir = os.path.dirname(os.path.abspath(args.doc))
    rel_out = os.path.relpath(os.path.abspath(args.out), doc_dir)
    rays = None
    if args.rays and os.path.exists(args.rays):
        with open(args.rays) as f:
            rays = list(csv.DictReader(f))
    splice_section(args.doc, section(rows, run, rel_out, args.out, rays), BEGIN, END)
    print("charts2d: wrote the 2D section of %s" % args.doc, file=sys.stderr)


if __name__ == "__main__":
    main()
