"""The visible albedo of each measured ground spectrum, computed apart from the Rust code.

The visible albedo is the mean albedo over 400-700 nm weighted by the sun's spectrum:

    A = integral(E(l) * a(l) dl) / integral(E(l) dl),   l from 400 to 700 nm,

with E the ASTM G173-03 extraterrestrial irradiance and a the ground's measured albedo, both
taken as the straight lines between their tabulated points. This script integrates that exactly:
on the merged grid of both tables' points each product is a quadratic, which Simpson's rule
integrates without error. (The crate takes the midpoint rule on 1 nm steps; the two agree to
about 1e-3.)

Reads, from the repository root:
    model/data/solar_etr_astm_g173.csv
    model/data/ground_albedo/*.csv      (wavelength in nm, or in um for the USGS ocean)

Run:  python3 tests/scripts/ground_visible_albedo.py
Its output is the table `INDEPENDENT` in `model/src/ground.rs`'s tests.
"""

import csv
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
VISIBLE_NM = (400.0, 700.0)

# The ground types of `GroundType`, their files and their wavelength column's unit in nm.
GROUNDS = [
    ("FreshSnow", "bowker1985_dry_fresh_snow.csv", "wavelength_nm", 1.0),
    ("Grass", "feister_grewe1995_grass.csv", "wavelength_nm", 1.0),
    ("DesertSand", "feister_grewe1995_sand.csv", "wavelength_nm", 1.0),
    ("DrySoil", "feister_grewe1995_loam.csv", "wavelength_nm", 1.0),
    ("Ocean", "usgs_splib06a_seawater_open_ocean.csv", "wavelength_um", 1000.0),
]


def read_table(path, x_column, y_column, x_scale):
    """The (x, y) points of a CSV file whose comment lines start with '#', sorted by x."""
    with open(path, newline="") as f:
        rows = csv.DictReader(line for line in f if line.strip() and not line.startswith("#"))
        points = [(float(r[x_column]) * x_scale, float(r[y_column])) for r in rows]
    points.sort()
    return points


def linear(points):
    """The straight lines between the points; past either end the end value holds."""

    def at(x):
        if x <= points[0][0]:
            return points[0][1]
        if x >= points[-1][0]:
            return points[-1][1]
        lo, hi = 0, len(points) - 1
        while hi - lo > 1:
            mid = (lo + hi) // 2
            if points[mid][0] <= x:
                lo = mid
            else:
                hi = mid
        (x0, y0), (x1, y1) = points[lo], points[hi]
        return y0 + (y1 - y0) * (x - x0) / (x1 - x0)

    return at


def integral(f, knots):
    """The integral of f over the knots, exact for a quadratic between neighbouring knots."""
    total = 0.0
    for a, b in zip(knots, knots[1:]):
        total += (b - a) / 6.0 * (f(a) + 4.0 * f(0.5 * (a + b)) + f(b))
    return total


def main():
    lo, hi = VISIBLE_NM
    sun_points = read_table(
        os.path.join(ROOT, "model/data/solar_etr_astm_g173.csv"),
        "wavelength_nm", "irradiance_W_m2_nm", 1.0)
    sun = linear(sun_points)
    print("ground       visible albedo (400-700 nm, ASTM G173 sun)")
    for name, file, column, scale in GROUNDS:
        points = read_table(os.path.join(ROOT, "model/data/ground_albedo", file), column, "albedo", scale)
        albedo = linear(points)
        knots = sorted({lo, hi} | {x for x, _ in sun_points + points if lo < x < hi})
        weighted = integral(lambda x: sun(x) * albedo(x), knots)
        total = integral(sun, knots)
        print(f"{name:<12} {weighted / total:.4f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
