//! Gałaj, Pietrusiak, Galewski, Ledzion, Wojciechowski (2021), "Hybrid Integration Method for
//! Sunlight Atmospheric Scattering" (IEEE Access 9), their spline transmittance: single
//! scattering marched along the view ray as in `trapezoid`, with the optical depth towards the
//! sun integrated in closed form over a cubic Hermite spline of the integrand instead of an
//! inner march.
//!
//! A ray's line is described by its distance `d` from the planet's centre and the distance `t`
//! along it from its point nearest the centre. Two meshes of the integrand are built once per
//! atmosphere (the [`MESH`] table), per constituent (air and aerosol as fitted exponentials,
//! `shared::exponential`; ozone as its thin shell):
//! - region I, lines that pass above the ground (R ≤ d ≤ R_top): exp(−(√(d² + t²) − R)/H) on
//!   t ∈ [0, √(R_top² − R²)] × d ∈ [R, R_top], the part beyond the top included as the paper
//!   does, so that every line's stretch inside the atmosphere lies on the mesh;
//! - region II, lines that meet the ground (d < R), in altitude instead of distance:
//!   exp(−h/H)·(h + R)/√((h + R)² − d²) (the integrand times dt/dh) on h ∈ [0, R_top − R] ×
//!   d ∈ {j·R/K}, j < K, which stops short of the integrand's singularity at d = R.
//!
//! A ray's column is then: the mesh interpolated across `d` at each node along the ray
//! (Hermite, Catmull–Rom tangents), and that 1-D spline integrated exactly between the ray's
//! ends. The paper's choice, Hermite splines with [`ALONG`] = 50 nodes along the ray and
//! [`ACROSS`] = 20 across (their Table 3), is kept. Lines that meet the ground beyond the
//! mesh's last column (d > (K − 1)/K·R: from the ground, a sun lower than 18°) read that
//! column; the domain keeps the sun higher.

use super::shared::exponential::ExponentialMedium;
use super::shared::moving_sky;
use super::shared::single_scattering_sky::{self, Way};
use super::shared::{Lanes, Lut, Params, TableSpec, Viewpoint};
use super::{Domain, Inputs, SkyModel};
use crate::geometry::rho_squared;

/// Mesh nodes along a ray (t or h): the paper's 50 "height points".
pub const ALONG: u32 = 50;
/// Mesh nodes across rays (d): the paper's 20 "distance points".
pub const ACROSS: u32 = 20;

/// The integrand's meshes, texel (i along, j across): lanes (air in region I, air in region
/// II, aerosol in region I, aerosol in region II), per unit ground density.
pub const MESH: TableSpec = TableSpec {
    id: "galaj-spline-mesh",
    label: "Gałaj spline mesh",
    size: [ALONG, ACROSS, 1],
    axes: [
        "along the ray: t (region I) or h (region II)",
        "across: d, the line's distance from the centre",
        "—",
    ],
    invalidated_by: Inputs::ATMOSPHERE,
    transmittance: false,
    describe_texel: describe_mesh_texel,
};

/// The model's tables: the mesh, then for views in motion the way to the sun tabulated and
/// the moving sky built from it (`shared::moving_sky`).
pub const TABLES: [TableSpec; 3] = [
    MESH,
    single_scattering_sky::SUN_ROUTE_TABLE,
    moving_sky::TABLE,
];

/// With Hillaire's higher orders (the `galaj-spline-ms` row): the mesh, the transmittance and
/// Ψ_ms tables, then the way to the sun tabulated and the moving sky.
pub const TABLES_MS: [TableSpec; 5] = [
    MESH,
    single_scattering_sky::TABLES_WITH_HIGHER_ORDERS[0],
    single_scattering_sky::TABLES_WITH_HIGHER_ORDERS[1],
    single_scattering_sky::SUN_ROUTE_TABLE,
    moving_sky::TABLE,
];

/// Daylight with the sun at least 18° high: lower, lines from the ground towards the sun leave
/// the mesh (d > 0.95·R), and the optical depth along them comes from its last column, too
/// small (a horizontal ray's by 95 %, `atmoscope bench transmittance`). From higher up the
/// band beyond the mesh reaches a little higher (19.5° at 10 km, 21° at the top), where the
/// air above is thin.
pub const DOMAIN: Domain = Domain {
    min_sun_elevation_deg: 18.0,
    note: "ground, plane and space views with the sun at least 18° high, where the spline's mesh ends seen from the ground; single scattering only",
    ..super::nishita::DOMAIN
};

/// The domain with Hillaire's higher orders added (the `galaj-spline-ms` row). No AOD passes
/// the registry's criterion, which asks for a sun 5° high too: there, below the mesh, the
/// sunlight is too bright; with the sun 30° high the sky stays within 25 % up to AOD 0.5
/// (`atmoscope bench aod`).
pub const DOMAIN_MS: Domain = Domain {
    max_aod550: 0.0,
    min_sun_elevation_deg: 18.0,
    note: "ground, plane and space views with the sun at least 18° high; Hillaire's isotropic higher orders added to single scattering",
    ..super::nishita::DOMAIN_MS
};

/// The registry's constructor (no table depends on the viewpoint).
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::GalajSpline, false)
}

/// The constructor of the `galaj-spline-ms` row: with Hillaire's multiple-scattering table.
pub fn build_ms(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    single_scattering_sky::build(params, Way::GalajSpline, true)
}

/// Spacing of the mesh along the ray in region I, m: √(R_top² − R²)/(N − 1).
fn region_one_step(p: &Params) -> f64 {
    let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
    ((top - big_r) * (top + big_r)).sqrt() / f64::from(ALONG - 1)
}

/// Spacing of the mesh along the ray in region II (altitude), m.
fn region_two_step(p: &Params) -> f64 {
    p.thickness_m() / f64::from(ALONG - 1)
}

/// d − R of mesh column `j` in region I, m (≥ 0).
fn region_one_d_above(p: &Params, j: f64) -> f64 {
    j * p.thickness_m() / f64::from(ACROSS - 1)
}

/// d of mesh column `j` in region II, m (< R).
fn region_two_d(p: &Params, j: f64) -> f64 {
    j * p.bottom_radius_m / f64::from(ACROSS)
}

/// The mesh of the scene's fitted medium (the GPU's `galaj_spline/mesh.wgsl`); the same in
/// every layer.
pub fn compute_mesh_lut(p: &Params) -> Lut {
    let medium = ExponentialMedium::fit(p);
    let big_r = p.bottom_radius_m;
    Lut::from_spec(&MESH, p.batches.len(), |_, _, j, i| {
        // Region I: the altitude at (t, d), √(d² + t²) − R, without cancellation.
        let t = i as f64 * region_one_step(p);
        let above = region_one_d_above(p, j as f64);
        let d2_minus_r2 = above * (2.0 * big_r + above);
        let h1 = (d2_minus_r2 + t * t) / ((d2_minus_r2 + big_r * big_r + t * t).sqrt() + big_r);
        // Region II: the integrand in altitude, dt/dh = r/√(r² − d²).
        let h2 = i as f64 * region_two_step(p);
        let (r, d) = (big_r + h2, region_two_d(p, j as f64));
        let jacobian = r / ((r - d) * (r + d)).sqrt();
        let e = |h: f64, big_h: f64| (-h / big_h).exp();
        let (air, aerosol) = (medium.air.scale_height_m, medium.aerosol.scale_height_m);
        Lanes([
            e(h1, air),
            e(h2, air) * jacobian,
            e(h1, aerosol),
            e(h2, aerosol) * jacobian,
        ])
    })
}

fn describe_mesh_texel(p: &Params, _: f64, [x, y, _]: [f64; 3]) -> String {
    format!(
        "region I: t = {:.0} km, d − R = {:.2} km; region II: h = {:.2} km, d = {:.0} km",
        x * region_one_step(p) / 1000.0,
        region_one_d_above(p, y) / 1000.0,
        x * region_two_step(p) / 1000.0,
        region_two_d(p, y) / 1000.0,
    )
}

/// The tangent at node `k` of `n` values `v(k)` by central differences (one-sided at the
/// ends): the Catmull–Rom choice.
fn tangent(v: impl Fn(usize) -> Lanes, k: usize, n: usize) -> Lanes {
    let (a, b) = (k.saturating_sub(1), (k + 1).min(n - 1));
    let (va, vb) = (v(a), v(b));
    Lanes::from_fn(|l| (vb[l] - va[l]) / (b - a) as f64)
}

/// The cubic Hermite spline through `v(0..n)` (unit spacing) at `x` ∈ [0, n − 1].
fn hermite(v: impl Fn(usize) -> Lanes + Copy, x: f64, n: usize) -> Lanes {
    let k = (x.floor().max(0.0) as usize).min(n - 2);
    let s = (x - k as f64).clamp(0.0, 1.0);
    let (p0, p1) = (v(k), v(k + 1));
    let (m0, m1) = (tangent(v, k, n), tangent(v, k + 1, n));
    let (s2, s3) = (s * s, s * s * s);
    let (h00, h10, h01, h11) = (
        2.0 * s3 - 3.0 * s2 + 1.0,
        s3 - 2.0 * s2 + s,
        -2.0 * s3 + 3.0 * s2,
        s3 - s2,
    );
    h00 * p0 + h10 * m0 + h01 * p1 + h11 * m1
}

/// ∫ over [0, s] (s ∈ [0, 1]) of the Hermite segment with ends `p0`, `p1` and tangents `m0`,
/// `m1` (unit spacing): the antiderivatives of the four basis functions.
fn segment_integral(p0: f64, m0: f64, p1: f64, m1: f64, s: f64) -> f64 {
    let (s2, s3, s4) = (s * s, s * s * s, s * s * s * s);
    p0 * (s - s3 + 0.5 * s4)
        + m0 * (0.5 * s2 - 2.0 / 3.0 * s3 + 0.25 * s4)
        + p1 * (s3 - 0.5 * s4)
        + m1 * (-s3 / 3.0 + 0.25 * s4)
}

/// ∫ from `a` to `b` (0 ≤ a ≤ b ≤ n − 1, unit spacing, n ≤ [`ALONG`]) of the Hermite spline
/// through `v(0..n)`, per lane; each node `v(k)` the range needs is evaluated once, as the
/// GPU's sliding window does.
fn spline_integral(v: impl Fn(usize) -> Lanes, a: f64, b: f64, n: usize) -> Lanes {
    let mut total = [0.0; 4];
    if b <= a {
        return Lanes(total);
    }
    let first = (a.floor().max(0.0) as usize).min(n - 2);
    let last = ((b.ceil() as usize).max(1) - 1).min(n - 2);
    let mut nodes = [[0.0; 4]; ALONG as usize];
    let (lo, hi) = (first.saturating_sub(1), (last + 2).min(n - 1));
    for (k, node) in nodes.iter_mut().enumerate().take(hi + 1).skip(lo) {
        *node = v(k).0;
    }
    let node = |k: usize| Lanes(nodes[k]);
    for k in first..=last {
        let (s0, s1) = (
            (a - k as f64).clamp(0.0, 1.0),
            (b - k as f64).clamp(0.0, 1.0),
        );
        let (p0, p1, m0, m1) = (
            node(k),
            node(k + 1),
            tangent(node, k, n),
            tangent(node, k + 1, n),
        );
        for l in 0..4 {
            total[l] += segment_integral(p0[l], m0[l], p1[l], m1[l], s1)
                - segment_integral(p0[l], m0[l], p1[l], m1[l], s0);
        }
    }
    Lanes(total)
}

/// ∫ exp(−h'/H) along the ray from altitude `h` (m) with zenith cosine `mu` to the top of the
/// atmosphere, m, for air and aerosol (their fitted scale heights, the mesh's lanes), by the
/// spline over `mesh` ([`compute_mesh_lut`]), floored at zero where the spline overshoots
/// below it (aerosol far above its layer). A descending line that meets the ground (only
/// the sun's partly hidden disk asks for one) is taken as grazing it, as `galaj_taylor` does.
pub fn columns(p: &Params, mesh: &Lut, h: f64, mu: f64) -> (f64, f64) {
    let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
    let (n, k) = (ALONG as usize, ACROSS as usize);
    let r = big_r + h;
    let t_p = r * mu;
    let mut d2_minus_r2 = rho_squared(h, big_r) - t_p * t_p;
    if mu < 0.0 {
        d2_minus_r2 = d2_minus_r2.max(0.0);
    }
    if d2_minus_r2 >= 0.0 {
        // Region I: from t_p (behind the nearest point when descending) to the top.
        let step = region_one_step(p);
        let above = d2_minus_r2 / ((d2_minus_r2 + big_r * big_r).sqrt() + big_r);
        let y = above / p.thickness_m() * (k - 1) as f64;
        let row = |i: usize| hermite(|j| mesh.texel(0, i, j, 0), y, k);
        let t_top = ((top - big_r) * (top + big_r) - d2_minus_r2)
            .max(0.0)
            .sqrt();
        let (x_p, x_top) = (t_p.abs() / step, t_top / step);
        let mut c = spline_integral(row, x_p, x_top, n);
        if mu < 0.0 {
            let back = spline_integral(row, 0.0, x_p, n);
            c = c + 2.0 * back;
        }
        (step * c[0].max(0.0), step * c[2].max(0.0))
    } else {
        // Region II (rising, d < R): in altitude, from h to the top.
        let step = region_two_step(p);
        let d = (d2_minus_r2 + big_r * big_r).max(0.0).sqrt();
        let y = (d / big_r * k as f64).min((k - 1) as f64);
        let row = |i: usize| hermite(|j| mesh.texel(0, i, j, 0), y, k);
        let c = spline_integral(row, h / step, (n - 1) as f64, n);
        (step * c[1].max(0.0), step * c[3].max(0.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::exponential::column_by_quadrature;
    use crate::methods::shared::optics::tests::params;
    use crate::methods::shared::single_scattering_sky::SunRoute;

    /// A Hermite spline reproduces a cubic's integral exactly where the tangents are exact
    /// (interior of a quadratic, whose central differences are exact).
    #[test]
    fn the_spline_integral_of_a_quadratic_is_exact() {
        let v = |i: usize| {
            let x = i as f64;
            Lanes([x * x, 2.0 * x + 1.0, 3.0, 0.0])
        };
        // From 1.25 to 4.5 on nodes 0..8: away from the one-sided end tangents.
        let got = spline_integral(v, 1.25, 4.5, 8);
        let exact = |x: f64| [x * x * x / 3.0, x * x + x, 3.0 * x, 0.0];
        for l in 0..4 {
            let want = exact(4.5)[l] - exact(1.25)[l];
            assert!((got[l] - want).abs() < 1e-12, "lane {l}: {got:?}");
        }
        // The interpolant passes through the nodes.
        assert_eq!(hermite(v, 3.0, 8), v(3));
    }

    /// The spline's optical depth towards the sun follows the quadrature through the fitted
    /// medium within 5 % from the ground in the domain, where the aerosol's column, read from
    /// mesh nodes 2 km apart (1.5 of its scale heights), comes out 8 % high and the air's
    /// within 0.2 %; within 3 % from 5 and 10 km. Along a line that dips to 6 km the spline
    /// across lines 5 km apart overshoots the aerosol below zero (floored: 12.3 % short at
    /// 640 nm, where aerosol makes more of the column than at shorter wavelengths). Every
    /// column, across heights and directions, is finite and not negative.
    #[test]
    fn the_spline_optical_depth_follows_quadrature_and_stays_positive() {
        let p = params();
        let route = SunRoute::new(&p, Way::GalajSpline);
        let m = ExponentialMedium::fit(&p);
        let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
        let exact = |h, mu| {
            m.optical_depth(&p, 0, h, mu, |h, mu, hh| {
                column_by_quadrature(h, mu, hh, big_r, top)
            })
        };
        for (h, elevation_deg, bound) in [
            (0.0, 90.0f64, 0.05),
            (0.0, 45.0, 0.05),
            (0.0, 30.0, 0.05),
            (5_000.0, 20.0, 0.03),
            (10_000.0, 2.0, 0.02),
            (30_000.0, -5.0, 0.13),
        ] {
            let mu = elevation_deg.to_radians().sin();
            let (got, want) = (route.optical_depth(&p, 0, h, mu), exact(h, mu));
            for l in 0..4 {
                assert!(
                    (got[l] / want[l] - 1.0).abs() < bound,
                    "h {h} sun {elevation_deg}°: {got:?} vs {want:?}"
                );
            }
        }
        let mesh = route.mesh.as_ref().expect("the spline's mesh");
        for h in [0.0, 3_000.0, 10_000.0, 40_000.0, 99_000.0] {
            for i in 0..=40 {
                let mu = -0.2 + 1.2 * f64::from(i) / 40.0;
                let (air, aerosol) = columns(&p, mesh, h, mu);
                assert!(
                    air.is_finite() && aerosol.is_finite() && air >= 0.0 && aerosol >= 0.0,
                    "h {h} mu {mu}: {air}, {aerosol}"
                );
            }
        }
    }
}
