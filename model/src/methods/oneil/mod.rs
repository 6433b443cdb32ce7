//! O'Neil (2005), "Accurate Atmospheric Scattering" (GPU Gems 2, ch. 16): Nishita's single
//! scattering made cheap enough for the GPUs of its day, and the sky of many games since. Two
//! shortcuts make it: the optical depth from a point at altitude h along a direction of zenith
//! cosine μ to the top is e^(−h/H)·H·scale(μ), one fitted function of the angle times the
//! density at the point ("scale" in the chapter: e^(p(x)), p a quartic in x = 1 − μ, fitted to
//! the integrated optical depth); and the view ray is marched in a few samples
//! ([`SAMPLES`]), the optical depth from the camera to each sample and from it to the sun
//! both taken from that function. Air and aerosol share one scale height H; no ozone; the
//! Rayleigh phase 3/4·(1 + ν²) and the chapter's aerosol phase
//! 3(1 − g²)/(2(2 + g²))·(1 + ν²)/(1 + g² − 2gν)^(3/2), both over 4π.
//!
//! The chapter's fit is for its own planet (the atmosphere 2.5 % of the radius, H a quarter of
//! it) and, it says, must be redone for another; here it is refitted ([`ScaleFit::new`]) to
//! the scene's planet, top of the atmosphere and the scale height of its air (the exponential
//! fit of `shared::exponential`): p₀ the zenith's value, p₁–p₄ by least squares on
//! ln(column / H) over μ from 0 to 1 (how closely it follows the column is the test
//! `the_scale_function_follows_the_integrated_column`). Each
//! constituent keeps its vertical optical depth (its column over H at the ground). Rays that
//! meet the ground take the chapter's ground formulation: the angles at the ground point, the
//! depth towards the camera as the difference of two looks up from below; the ground is
//! Lambertian under the attenuated sun. No higher orders, no Earth shadow (the fit extrapolates
//! below the horizon). [`sky`] is the twin of `shaders/oneil/sky.wgsl`.

pub mod sky;

use super::shared::exponential::{ExponentialMedium, column_by_quadrature};
use super::shared::sun_disk::visible_fraction;
use super::shared::{Lanes, Lut, Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};
use glam::DVec3;

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// Samples along the view ray ("a few": the chapter's shaders take 2 to 5).
pub const SAMPLES: u32 = 5;

/// Points of x = 1 − μ over [0, 1] the scale function is fitted to.
pub const FIT_POINTS: usize = 64;

/// As single scattering's (`nishita`'s): ground, plane and space views in daylight; no AOD
/// range.
pub const DOMAIN: Domain = Domain {
    note: "ground, plane and space views in daylight; single scattering in five samples with a fitted optical depth, one scale height, no ozone",
    ..super::nishita::DOMAIN
};

/// The scale function and the medium it serves: optical depth to the top from altitude h along
/// zenith cosine μ = e^(−h/H)·H·e^(p(1 − μ)) per unit ground density.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ScaleFit {
    /// p₀…p₄ of the quartic in x = 1 − μ.
    pub coefficients: [f64; 5],
    /// The shared scale height H, m: the air's.
    pub scale_height_m: f64,
    /// Ground densities (relative air density; m⁻¹ per unit of the aerosol coefficients) that
    /// keep each constituent's column with the shared H.
    pub air_at_ground: f64,
    pub aerosol_at_ground: f64,
}

/// Solves the N × N system `a`·x = `b` by Gaussian elimination with partial pivoting.
fn solve<const N: usize>(mut a: [[f64; N]; N], mut b: [f64; N]) -> [f64; N] {
    for col in 0..N {
        let pivot = (col..N)
            .max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))
            .unwrap_or(col);
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..N {
            let f = a[row][col] / a[col][col];
            for k in col..N {
                a[row][k] -= f * a[col][k];
            }
            b[row] -= f * b[col];
        }
    }
    let mut x = [0.0; N];
    for row in (0..N).rev() {
        let s: f64 = (row + 1..N).map(|k| a[row][k] * x[k]).sum();
        x[row] = (b[row] - s) / a[row][row];
    }
    x
}

impl ScaleFit {
    /// The fit for the scene of `p`.
    pub fn new(p: &Params) -> ScaleFit {
        let m = ExponentialMedium::fit(p);
        let h = m.air.scale_height_m;
        let (big_r, top) = (p.bottom_radius_m, p.top_radius_m);
        let ln_column = |mu: f64| (column_by_quadrature(0.0, mu, h, big_r, top) / h).ln();
        // p₀ is the zenith's value, as in the chapter's fit (its p₀ = −0.00287 makes scale(1)
        // the vertical column); p₁…p₄ by least squares on the rest.
        let p0 = ln_column(1.0);
        let mut ata = [[0.0; 4]; 4];
        let mut atb = [0.0; 4];
        for k in 1..FIT_POINTS {
            let x = k as f64 / (FIT_POINTS - 1) as f64;
            let y = ln_column(1.0 - x) - p0;
            let powers: [f64; 4] = std::array::from_fn(|i| x.powi(i as i32 + 1));
            for i in 0..4 {
                for j in 0..4 {
                    ata[i][j] += powers[i] * powers[j];
                }
                atb[i] += powers[i] * y;
            }
        }
        let [p1, p2, p3, p4] = solve(ata, atb);
        ScaleFit {
            coefficients: [p0, p1, p2, p3, p4],
            scale_height_m: h,
            air_at_ground: m.air.at_ground * m.air.scale_height_m / h,
            aerosol_at_ground: m.aerosol.at_ground * m.aerosol.scale_height_m / h,
        }
    }

    /// The chapter's scale(μ) in units of H: column to the top from the ground along zenith
    /// cosine `mu`, over H.
    pub fn scale(&self, mu: f64) -> f64 {
        let x = 1.0 - mu;
        let c = &self.coefficients;
        (c[0] + x * (c[1] + x * (c[2] + x * (c[3] + x * c[4])))).exp()
    }

    /// The density factor e^(−h/H) at altitude `h`.
    pub fn density(&self, h: f64) -> f64 {
        (-h / self.scale_height_m).exp()
    }

    /// The values the GPU reads from `globals.model`: p₀–p₃; p₄, H, the air's and the
    /// aerosol's ground densities; the samples.
    pub fn constants(&self) -> [f64; 12] {
        let c = &self.coefficients;
        [
            c[0],
            c[1],
            c[2],
            c[3],
            c[4],
            self.scale_height_m,
            self.air_at_ground,
            self.aerosol_at_ground,
            f64::from(SAMPLES),
            0.0,
            0.0,
            0.0,
        ]
    }
}

/// The model's constants for the GPU.
pub fn constants(p: &Params) -> [f64; 12] {
    ScaleFit::new(p).constants()
}

/// O'Neil's sky for one atmosphere.
#[derive(Debug, Clone)]
pub struct ONeil {
    pub params: Params,
    pub fit: ScaleFit,
}

impl SkyModel for ONeil {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        sky::radiance(&self.params, &self.fit, layer, at, dir, sun)
    }

    fn table(&self, _: &str) -> Option<&Lut> {
        None
    }

    /// The sun's disk through the fitted optical depth towards it.
    fn sun(&self, layer: usize, h: f64, mu_s: f64, disk: Lanes) -> Lanes {
        let p = &self.params;
        let visible = visible_fraction(h, mu_s, p.bottom_radius_m);
        let depth = self.fit.density(h.min(p.thickness_m()))
            * self.fit.scale(mu_s)
            * self.fit.scale_height_m;
        let t = sky::extinction(p, &self.fit, layer).map(|e| (-e * depth).exp());
        p.batches[layer].solar_irradiance * t * visible * disk.map(|d| d.max(0.0))
    }
}

/// The registry's constructor.
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(ONeil {
        fit: ScaleFit::new(params),
        params: params.clone(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::methods::shared::optics::tests::params;

    /// The refitted scale function is exact at the zenith (the vertical column, 1 in units of
    /// H) and follows the integrated column within 5 % down to μ = 0.2, 9 % to μ = 0.05 and
    /// 18 % at the horizon: the chapter's quartic in 1 − μ cannot follow the steep rise at the
    /// horizon of an atmosphere as thin as Earth's (R/H ≈ 860; the chapter's planet had 160).
    #[test]
    fn the_scale_function_follows_the_integrated_column() {
        let p = params();
        let fit = ScaleFit::new(&p);
        let h = fit.scale_height_m;
        assert!((5_000.0..12_000.0).contains(&h), "{h}");
        for (mu, bound) in [
            (1.0, 1e-6),
            (0.8, 0.05),
            (0.5, 0.05),
            (0.3, 0.05),
            (0.2, 0.05),
            (0.1, 0.09),
            (0.05, 0.09),
            (0.0, 0.18),
        ] {
            let want = column_by_quadrature(0.0, mu, h, p.bottom_radius_m, p.top_radius_m) / h;
            let got = fit.scale(mu);
            assert!((got / want - 1.0).abs() < bound, "mu {mu}: {got} vs {want}");
        }
        assert!((fit.scale(1.0) - 1.0).abs() < 0.01);
    }

    /// The constituents keep their vertical optical depth under the shared scale height.
    #[test]
    fn each_constituent_keeps_its_column() {
        let p = params();
        let fit = ScaleFit::new(&p);
        let m = ExponentialMedium::fit(&p);
        let air = fit.air_at_ground * fit.scale_height_m;
        let aerosol = fit.aerosol_at_ground * fit.scale_height_m;
        assert!((air / (m.air.at_ground * m.air.scale_height_m) - 1.0).abs() < 1e-12);
        assert!(
            (aerosol - m.aerosol.at_ground * m.aerosol.scale_height_m).abs()
                <= 1e-12 * aerosol.abs().max(1e-30)
        );
    }

    /// The elimination solves a least-squares system of an exact quartic.
    #[test]
    fn the_solver_recovers_a_quartic() {
        let want = [0.3, -1.2, 2.5, 0.7, -0.4];
        let mut ata = [[0.0; 5]; 5];
        let mut atb = [0.0; 5];
        for k in 0..20 {
            let x = k as f64 / 19.0;
            let y: f64 = (0..5).map(|i| want[i] * x.powi(i as i32)).sum();
            for i in 0..5 {
                for j in 0..5 {
                    ata[i][j] += x.powi(i as i32) * x.powi(j as i32);
                }
                atb[i] += x.powi(i as i32) * y;
            }
        }
        let got = solve(ata, atb);
        for (g, w) in got.iter().zip(want) {
            assert!((g - w).abs() < 1e-8, "{got:?}");
        }
    }
}
