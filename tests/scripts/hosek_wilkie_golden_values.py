#!/usr/bin/env python3
"""Golden values of the Hosek-Wilkie sky model, computed apart from the Rust code.

The Rust test `the_fit_gives_the_values_worked_out_from_its_tables`
(model/src/methods/hosek_wilkie/mod.rs) checks six numbers; they are this script's output.
It evaluates the published fit straight from the tables the crate embeds, with the standard
library only:

- model/data/hosek_wilkie2012_sky_spectral.csv and hosek_wilkie2012_sky_rgb.csv: the sky of
  L. Hosek, A. Wilkie (2012), "An Analytic Model for Full Spectral Sky-Dome Radiance",
  ACM Transactions on Graphics 31(4), 95:

      L(theta, gamma) = (1 + A exp(B / (cos theta + 0.01)))
                        * (C + D exp(E gamma) + F cos^2 gamma + G chi(H, gamma) + I sqrt(cos theta))
                        * L_M,
      chi(g, gamma) = (1 + cos^2 gamma) / (1 + g^2 - 2 g cos gamma)^(3/2),

  theta the view's zenith angle, gamma its angle from the sun. Each of A-I and L_M is a
  quintic Bezier curve over six control points in x = (solar elevation / (pi/2))^(1/3), then
  linear in turbidity between the integer turbidities around T (10 is the top of 9-10) and
  linear in ground albedo between 0 and 1.
- model/data/hosek_wilkie2013_sun.csv: the solar radiance function of L. Hosek, A. Wilkie
  (2013), "Adding a Solar Radiance Function to the Hosek Skylight Model", IEEE Computer
  Graphics and Applications 33(3), 44-52: the radiance at the centre of the sun's disk per band
  and turbidity, 45 cubic pieces in the elevation e, piece k starting at e_k = (k/45)^3 pi/2
  and used while k/45 <= (e/(pi/2))^(1/3) < (k+1)/45; linear in turbidity as the sky.
- model/data/hosek_wilkie2013_limb_darkening.csv: the sun's limb darkening. None of the six
  values uses it; its mean over the disk is printed as context, integrated numerically.

The arguments are those of the test's calls: `radiance(channel, T, albedo, elevation_deg,
theta_deg, gamma_deg)` (a channel is a spectral band, named by its centre in nm, or an sRGB
primary) and `sun_centre_radiance(band, T, elevation_rad)`.

Run from the repository root:

    python3 tests/scripts/hosek_wilkie_golden_values.py

It prints each value beside the test's and their relative difference (the test allows 1e-5),
and exits with status 1 if any differs by more.
"""

import csv
import math
import sys
from pathlib import Path

DATA = Path(__file__).resolve().parents[2] / "model" / "data"
TOLERANCE = 1e-5
SUN_PIECES = 45
SUN_RADIUS_DEG = 0.255


def rows(name):
    """The rows of a CSV table in model/data as dicts, skipping the '#' header comments."""
    with open(DATA / name, newline="") as f:
        return list(csv.DictReader(line for line in f if not line.startswith("#")))


def sky_table(name, channel_column):
    """{(channel, albedo, turbidity): six control points, each {coefficient name: value}}."""
    names = ["A", "B", "C", "D", "E", "F", "G", "H", "I", "L_M"]
    table = {}
    for r in rows(name):
        key = (r[channel_column], int(r["albedo"]), int(r["turbidity"]))
        points = table.setdefault(key, [None] * 6)
        points[int(r["control_point"])] = {n: float(r[n]) for n in names}
    # Every channel has 2 albedos x 10 turbidities x 6 points.
    assert all(p is not None for points in table.values() for p in points)
    return table


SPECTRAL = sky_table("hosek_wilkie2012_sky_spectral.csv", "band")
RGB = sky_table("hosek_wilkie2012_sky_rgb.csv", "channel")
# {(band, turbidity, piece): (c0, c1, c2, c3)}
SUN = {
    (r["band"], int(r["turbidity"]), int(r["piece"])): tuple(
        float(r[c]) for c in ("c0", "c1", "c2", "c3")
    )
    for r in rows("hosek_wilkie2013_sun.csv")
}
# {band: [d0, ..., d5]}
LIMB = {
    r["band"]: [float(r[f"d{k}"]) for k in range(6)]
    for r in rows("hosek_wilkie2013_limb_darkening.csv")
}


def bezier(points, x):
    """A Bezier curve at x by de Casteljau's construction (the same curve as the Bernstein sum
    of C(5,k) x^k (1-x)^(5-k) p_k, reached another way)."""
    p = list(points)
    while len(p) > 1:
        p = [(1 - x) * a + x * b for a, b in zip(p, p[1:])]
    return p[0]


def turbidity_weights(t):
    """[(integer turbidity, weight)]: linear between floor(T) and floor(T)+1; T = 10 is the
    upper end of 9-10."""
    low = min(int(math.floor(t)), 9)
    frac = t - low
    return [(low, 1 - frac), (low + 1, frac)]


def coefficients(table, channel, t, albedo, elevation_rad):
    """A-I and L_M for turbidity t, ground albedo and solar elevation (rad)."""
    x = (elevation_rad / (math.pi / 2)) ** (1 / 3)
    out = {}
    for a, wa in ((0, 1 - albedo), (1, albedo)):
        for turbidity, wt in turbidity_weights(t):
            if wa * wt == 0:
                continue
            points = table[(channel, a, turbidity)]
            for n in points[0]:
                out[n] = out.get(n, 0.0) + wa * wt * bezier([p[n] for p in points], x)
    return out


def radiance(table, channel, t, albedo, elevation_deg, theta_deg, gamma_deg):
    """The sky's radiance L(theta, gamma) of the 2012 paper (the unit of L_M)."""
    k = coefficients(table, channel, t, albedo, math.radians(elevation_deg))
    cos_theta = math.cos(math.radians(theta_deg))
    gamma = math.radians(gamma_deg)
    cos_gamma = math.cos(gamma)
    chi = (1 + cos_gamma**2) / (1 + k["H"] ** 2 - 2 * k["H"] * cos_gamma) ** 1.5
    gradation = 1 + k["A"] * math.exp(k["B"] / (cos_theta + 0.01))
    indicatrix = (
        k["C"]
        + k["D"] * math.exp(k["E"] * gamma)
        + k["F"] * cos_gamma**2
        + k["G"] * chi
        + k["I"] * math.sqrt(cos_theta)
    )
    return gradation * indicatrix * k["L_M"]


def sun_piece(elevation_rad):
    """The piece k with k/45 <= (e/(pi/2))^(1/3) < (k+1)/45 (the last one at the zenith)."""
    return min(int((elevation_rad / (math.pi / 2)) ** (1 / 3) * SUN_PIECES), SUN_PIECES - 1)


def sun_centre_radiance(band, t, elevation_rad):
    """The radiance at the sun's centre of the 2013 paper, W m^-2 sr^-1 nm^-1."""
    k = sun_piece(elevation_rad)
    u = elevation_rad - (k / SUN_PIECES) ** 3 * math.pi / 2
    total = 0.0
    for turbidity, w in turbidity_weights(t):
        if w == 0:
            continue
        c = SUN[(band, turbidity, k)]
        total += w * sum(c[n] * u**n for n in range(4))
    return total


def limb_mean(band, steps=20000):
    """The limb darkening's mean over the disk: the midpoint rule in the disk's radius
    fraction rho (area weight 2 rho), s = sqrt(1 - rho^2) the cosine across the disk."""
    d = LIMB[band]
    total = 0.0
    for i in range(steps):
        rho = (i + 0.5) / steps
        s = math.sqrt(1 - rho * rho)
        total += sum(dk * s**k for k, dk in enumerate(d)) * 2 * rho / steps
    return total


def main():
    # (what, computed, the test's number), in the test's order.
    cases = [
        (
            "560 nm, T 3, albedo 0, sun 90 deg, theta 0, gamma 0",
            radiance(SPECTRAL, "560", 3.0, 0.0, 90.0, 0.0, 0.0),
            0.133330,
        ),
        (
            "440 nm, T 2.5, albedo 0.5, sun 11.25 deg, theta 60, gamma 90",
            radiance(SPECTRAL, "440", 2.5, 0.5, 11.25, 60.0, 90.0),
            0.0663070,
        ),
        (
            "sRGB G, T 10, albedo 1, sun 45 deg, theta 30, gamma 20",
            radiance(RGB, "G", 10.0, 1.0, 45.0, 30.0, 20.0),
            58.5171,
        ),
        (
            "580 nm = (560 + 600)/2, T 4, albedo 0.3, sun 30 deg, theta 0, gamma 60",
            0.5 * radiance(SPECTRAL, "560", 4.0, 0.3, 30.0, 0.0, 60.0)
            + 0.5 * radiance(SPECTRAL, "600", 4.0, 0.3, 30.0, 0.0, 60.0),
            0.0283864,
        ),
        (
            f"sun centre 560 nm, T 3, 30 deg (piece {sun_piece(math.radians(30))}, from 0)",
            sun_centre_radiance("560", 3.0, math.radians(30.0)),
            18982.3,
        ),
        (
            f"sun centre 440 nm, T 2.5, 5 deg (piece {sun_piece(math.radians(5))}, from 0)",
            sun_centre_radiance("440", 2.5, math.radians(5.0)),
            977.914,
        ),
    ]
    failed = False
    print(f"{'case':<72} {'computed':>14} {'test':>12} {'rel. diff':>10}")
    for what, got, want in cases:
        rel = got / want - 1
        failed |= abs(rel) >= TOLERANCE
        flag = "" if abs(rel) < TOLERANCE else "  OUTSIDE 1e-5"
        print(f"{what:<72} {got:>14.7g} {want:>12.6g} {rel:>10.2e}{flag}")
    # Context, not checked by the test: the disk's mean limb darkening and irradiance.
    solid_angle = math.pi * math.sin(math.radians(SUN_RADIUS_DEG)) ** 2
    for band, t, e in (("560", 3.0, 30.0), ("440", 2.5, 5.0)):
        mean = limb_mean(band)
        centre = sun_centre_radiance(band, t, math.radians(e))
        print(
            f"(context) {band} nm limb darkening: centre {sum(LIMB[band]):.6f}, disk mean "
            f"{mean:.6f}; disk irradiance at T {t}, {e} deg: "
            f"{centre * mean * solid_angle:.6g} W/m^2/nm"
        )
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
