#!/usr/bin/env python3
"""Fit of the real-time models' polarisation correction for the higher orders.

What it fits: the two constants of `methods::shared::polarisation` (model/src/methods/shared/
polarisation.rs), β = MS_LIKE_SINGLE and α = MS_VERTICAL. The real-time models carry only
single scattering's polarisation (Q₁, U₁, radiance I₁); the rest of the light, the higher
orders' I_ms = max(0, I − I₁), is given the Stokes components

    (Q, U)_ms = I_ms·[β·(Q₁, U₁)/I₁ + α·sin²θ_v·(1, 0)]

so that (Q, U) = (Q₁, U₁)·(1 + β·I_ms/I₁) + α·sin²θ_v·I_ms·(1, 0), as the code writes it.
θ_v is the view's zenith angle; (1, 0) is light vibrating vertically, which in the app's
meridian frame (`model::polarisation`: e₁ = up towards the zenith, Q > 0 vertical) is
(cos 2χ_v, sin 2χ_v) with χ_v = 0. Views that end on the ground (zenith > 90°) and views whose
I₁ is 0 get no correction, and the predicted polarised part is capped at I, as in the code.

Where the data come from: `atmoscope probe --stokes --json`, once with `--method
single-scattering` (the exact single scattering: subscript 1) and once with `--method
path-tracer` (the vector path tracer: the total I, Q, U), for eight scenes (sun 30° and 5°;
clear air, and rural haze of AOD 0.2; grey ground of albedo 0.1 and 0.3), 49 directions (zenith
0, 15, 30, 45, 60, 75, 85°; azimuth 0–180° from the sun by 30°) and 450, 550, 650, 700 nm; the
higher orders are the tracer's less single scattering's. β and α are the linear least squares
of the residual Q_ms and U_ms, each divided by the tracer's I, over the chosen scenes (normal
equations, 2 × 2). The score is the absolute error of the degree of polarisation predicted
from (I, Q₁, U₁) against the tracer's, per scene, mean and 95th percentile, for unpolarised
higher orders (0, 0), the fitted pair and a given pair. The table of the section "The
correction for the higher orders" of docs/measurements/polarisation-2026-12-06.md came from
this fit (its fitted rows and its rural albedo 0.3 scenes predate the change of the aerosols'
matrix that section describes, so a rerun moves the rural numbers slightly).

How to run it, from the repository root (the full fit: 16 probe runs, the tracer's at 3 000
paths; use a release build, and keep the outputs):

    python3 docs/measurements/polarisation_fit.py --save /tmp/polfit-data
    python3 docs/measurements/polarisation_fit.py --data /tmp/polfit-data --scenes albedo0.1
    python3 docs/measurements/polarisation_fit.py --data /tmp/polfit-data --scenes clear,albedo0.1

Quick check (2 scenes, 16 directions, 200 paths; under a minute on a debug build):

    python3 docs/measurements/polarisation_fit.py --quick

`--data DIR` reads the outputs saved there by `--save DIR` (one JSON per scene and method, the
tracer's named by its paths, a quick run's marked -quick) and runs only those missing.
`--scenes` takes comma-separated tags a fitted scene must all match (clear, rural, albedo0.1,
albedo0.3, sun30, sun5, or all); the scores are given for every scene loaded.
"""

import argparse
import json
import math
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
WAVELENGTHS = [450, 550, 650, 700]
ZENITHS = [0, 15, 30, 45, 60, 75, 85]
AZIMUTHS = [0, 30, 60, 90, 120, 150, 180]
# --quick: fewer directions (the sun's own, 90° from it, the horizon and the zenith kept).
QUICK_ZENITHS = [0, 30, 60, 85]
QUICK_AZIMUTHS = [0, 60, 120, 180]
QUICK_SPP = 200

# The eight scenes: (name, tags, probe scene arguments).
SCENES = []
for air, aerosol, aod in (("clear", "none", "0"), ("rural", "rural", "0.2")):
    for sun in (30, 5):
        for albedo in ("0.1", "0.3"):
            SCENES.append((
                f"{air}-sun{sun}-albedo{albedo}",
                {air, f"sun{sun}", f"albedo{albedo}", "all"},
                ["--sun-elevation-deg", str(sun), "--aerosol", aerosol, "--aod550", aod,
                 "--albedo", albedo],
            ))
QUICK_SCENES = ["clear-sun30-albedo0.1", "rural-sun5-albedo0.1"]


def find_binary(given):
    if given:
        return Path(given)
    for build in ("release", "debug"):
        path = ROOT / "target" / build / "atmoscope"
        if path.exists():
            return path
    sys.exit("no atmoscope binary in target/release or target/debug: build it or give --atmoscope")


def probe(args, name, scene_args, method, zeniths, azimuths):
    """The probe's JSON for one scene and method: read from --data if there, else run (and
    keep it under --save)."""
    # The directions are in the name too: a quick run's files never stand in for a full run's.
    file = (f"{name}.{method}" + (f"-spp{args.spp}" if method == "path-tracer" else "")
            + ("-quick" if args.quick else "") + ".json")
    if args.data and (Path(args.data) / file).exists():
        return json.loads((Path(args.data) / file).read_text())
    command = [str(find_binary(args.atmoscope)), "probe",
               "--view-zenith-deg", ",".join(map(str, zeniths)),
               "--view-azimuth-deg", ",".join(map(str, azimuths)),
               "--wavelengths-nm", ",".join(map(str, WAVELENGTHS)),
               *scene_args, "--stokes", "--json", "--method", method]
    if method == "path-tracer":
        command += ["--spp", str(args.spp)]
    print(f"running {name} {method} ...", file=sys.stderr, flush=True)
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    if args.save:
        Path(args.save).mkdir(parents=True, exist_ok=True)
        (Path(args.save) / file).write_text(out)
    return json.loads(out)


def by_key(probe_json):
    """Samples keyed by (zenith, azimuth, wavelength), Stokes (I, Q, U, V)."""
    return {(s["view_zenith_deg"], s["view_azimuth_deg"], s["wavelength_nm"]): s["stokes"]
            for s in probe_json["samples"]}


def samples(single, traced, zeniths, azimuths):
    """One record per direction and wavelength: the tracer's (I, Q, U, V), single scattering's
    (I₁, Q₁, U₁) and the correction's two basis vectors, per unit β and per unit α."""
    ones, total = by_key(single), by_key(traced)
    out = []
    for z in zeniths:
        for a in azimuths:
            for w in WAVELENGTHS:
                key = (float(z), float(a), float(w))
                if key not in ones or key not in total:
                    sys.exit(f"no sample at zenith {z}°, azimuth {a}°, {w} nm in the probe output")
                (i, q, u, v), (i1, q1, u1, _) = total[key], ones[key]
                if i <= 0.0:
                    continue
                # The code: no correction over the ground or where single scattering is dark;
                # I_ms never negative (the tracer's noise can put I below I₁).
                i_ms = max(0.0, i - i1) if z <= 90 and i1 > 0.0 else 0.0
                like_single = (i_ms * q1 / i1, i_ms * u1 / i1) if i_ms > 0.0 else (0.0, 0.0)
                sin2 = math.sin(math.radians(z)) ** 2
                vertical = (sin2 * i_ms, 0.0)  # vertical in the meridian frame: Q > 0, U = 0
                out.append({"i": i, "q": q, "u": u, "v": v, "q1": q1, "u1": u1,
                            "x": like_single, "y": vertical})
    return out


def fit(records):
    """β, α minimising Σ over Q and U of ((total − single − β·x − α·y)/I)²."""
    sxx = sxy = syy = sxb = syb = 0.0
    for r in records:
        for k, (total, one) in enumerate(((r["q"], r["q1"]), (r["u"], r["u1"]))):
            x, y, b = r["x"][k] / r["i"], r["y"][k] / r["i"], (total - one) / r["i"]
            sxx, sxy, syy = sxx + x * x, sxy + x * y, syy + y * y
            sxb, syb = sxb + x * b, syb + y * b
    det = sxx * syy - sxy * sxy
    if det == 0.0:
        sys.exit("the normal equations are singular: too few samples with higher orders")
    return (syy * sxb - sxy * syb) / det, (sxx * syb - sxy * sxb) / det


def degree_errors(records, beta, alpha):
    """|P_predicted − P_tracer| per record, the prediction capped at a degree of 1."""
    errors = []
    for r in records:
        q = r["q1"] + beta * r["x"][0] + alpha * r["y"][0]
        u = r["u1"] + beta * r["x"][1] + alpha * r["y"][1]
        predicted = min(1.0, math.hypot(q, u) / r["i"])
        traced = min(1.0, math.sqrt(r["q"] ** 2 + r["u"] ** 2 + r["v"] ** 2) / r["i"])
        errors.append(abs(predicted - traced))
    return errors


def percentile(values, p):
    """Linear interpolation between closest ranks (numpy's default)."""
    s = sorted(values)
    at = (len(s) - 1) * p / 100.0
    lo = math.floor(at)
    hi = min(lo + 1, len(s) - 1)
    return s[lo] + (s[hi] - s[lo]) * (at - lo)


def score(records, pair):
    e = degree_errors(records, *pair)
    return f"{sum(e) / len(e):.3f} / {percentile(e, 95):.3f}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--atmoscope", help="the binary (default target/release/atmoscope, "
                        "else target/debug/atmoscope)")
    parser.add_argument("--data", help="folder of saved probe JSON outputs to read "
                        "(a missing one is run)")
    parser.add_argument("--save", help="folder to write the probe runs' JSON outputs to")
    parser.add_argument("--scenes", default="all",
                        help="tags the fitted scenes must all match, comma-separated: clear, "
                        "rural, albedo0.1, albedo0.3, sun30, sun5, all (default all)")
    parser.add_argument("--pair", default="0.44,0.15",
                        help="β,α to score beside the fit (default the code's 0.44,0.15)")
    parser.add_argument("--spp", type=int, help=f"tracer paths per direction (default 3000; "
                        f"{QUICK_SPP} with --quick)")
    parser.add_argument("--quick", action="store_true", help=f"only {', '.join(QUICK_SCENES)}, "
                        f"{len(QUICK_ZENITHS) * len(QUICK_AZIMUTHS)} directions, {QUICK_SPP} paths")
    args = parser.parse_args()
    args.spp = args.spp or (QUICK_SPP if args.quick else 3000)
    given = tuple(float(x) for x in args.pair.split(","))
    if len(given) != 2:
        sys.exit("--pair: two numbers, β,α")
    tags = set(args.scenes.split(","))
    known = set().union(*(t for _, t, _ in SCENES))
    if not tags <= known:
        sys.exit(f"--scenes: unknown {', '.join(sorted(tags - known))} (from {', '.join(sorted(known))})")
    zeniths, azimuths = (QUICK_ZENITHS, QUICK_AZIMUTHS) if args.quick else (ZENITHS, AZIMUTHS)
    scenes = [s for s in SCENES if not args.quick or s[0] in QUICK_SCENES]

    data = {}  # scene name → records
    for name, _, scene_args in scenes:
        single = probe(args, name, scene_args, "single-scattering", zeniths, azimuths)
        traced = probe(args, name, scene_args, "path-tracer", zeniths, azimuths)
        data[name] = samples(single, traced, zeniths, azimuths)

    fitted_scenes = [n for n, t, _ in scenes if tags <= t]
    if not fitted_scenes:
        sys.exit(f"--scenes {args.scenes}: no loaded scene matches")
    fitted_records = [r for n in fitted_scenes for r in data[n]]
    best = fit(fitted_records)
    print(f"fit over {len(fitted_records)} samples ({', '.join(fitted_scenes)}; tracer "
          f"{args.spp} paths): beta = {best[0]:.3f}, alpha = {best[1]:.3f}")
    print("degree of polarisation, absolute error against the tracer, mean / p95:")
    columns = [("unpolarised (0, 0)", (0.0, 0.0)),
               (f"fit {best[0]:.3f}, {best[1]:.3f}", best),
               (f"given {given[0]:g}, {given[1]:g}", given)]
    print(f"{'scene':24} {'n':>5}" + "".join(f"  {c:>20}" for c, _ in columns))
    everything = [r for n in data for r in data[n]]
    for name, records in list(data.items()) + [("all", everything)]:
        print(f"{name:24} {len(records):5}" + "".join(f"  {score(records, p):>20}"
                                                     for _, p in columns))


if __name__ == "__main__":
    main()
