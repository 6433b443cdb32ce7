//! Hosek & Wilkie (2012), "An Analytic Model for Full Spectral Sky-Dome Radiance" (ACM TOG
//! 31(4)), with the solar radiance function of Hosek & Wilkie (2013), "Adding a Solar Radiance
//! Function to the Hosek Skylight Model" (IEEE CG&A 33(3)): the sky seen from the ground as a
//! nine-parameter distribution per band,
//!
//! L(θ, γ) = (1 + A·e^(B / (cos θ + 0.01)))·(C + D·e^(Eγ) + F·cos²γ + G·χ(H, γ) + I·√cos θ)·L_M,
//! χ(g, γ) = (1 + cos²γ) / (1 + g² − 2g·cos γ)^(3/2),
//!
//! θ the view's zenith angle, γ its angle from the sun. Each of A–I and the radiance scale L_M
//! is a quintic Bézier curve in x = (solar elevation / (π/2))^(1/3) over six control points,
//! blended linearly between the two neighbouring integer turbidities and between ground albedo
//! 0 and 1 (the fit's tables, `model/data/hosek_wilkie2012_*.csv`, BSD-3-Clause). Eleven
//! bands, 320–720 nm, blended linearly between band centres; its own fit in linear sRGB
//! serves RGB3. Blender, Cycles, Mitsuba and pbrt ship it.
//!
//! The fit is for the daytime sky seen from the ground; outside that it refuses
//! (`Domain::refuses`). The turbidity comes from the scene as Preetham's does
//! (`OpticalDepth::turbidity`), held to 1–10; the ground albedo is the scene's. Above 720 nm
//! (SpectralN reaches 830 nm) the sky keeps the 720 nm band's ratio of radiance to solar
//! irradiance. The sun is the 2013 solar radiance function: the radiance at the disk's centre
//! through the fit's atmosphere and its limb darkening, whose mean over the disk sets the
//! disk's irradiance (the disk is drawn with the renderer's limb profile at that mean). The
//! ground, which the fit does not cover, is Lambertian under the fit's sun and sky. All of it
//! scales with the scene's solar irradiance over the default spectrum's at 1 AU (its sun's
//! spectrum and distance).
//!
//! Everything the GPU needs is computed on the CPU for the frame's sun: [`batch_rows`] gives
//! each batch the blended coefficients of the two bands around each lane, the sun's
//! transmittance and the ground's radiance, which the sky pass ([`sky`], twin of
//! `shaders/hosek_wilkie/sky.wgsl`) reads as `batches[layer].model`.

pub mod sky;

use super::shared::sun_rows::{RowSky, hemisphere_irradiance};
use super::shared::{BatchRows, Lanes, Params, TableSpec, Viewpoint};
use super::{Domain, SkyModel};
use crate::csv_table::{Table, tables};
use crate::solar_spectrum::SolarSpectrum;
use crate::wavelengths::{LANES, POINT_SET_SOLAR_BAND_NM};
use std::f64::consts::{FRAC_PI_2, PI};
use std::sync::OnceLock;

/// The method has no tables.
pub const TABLES: [TableSpec; 0] = [];

/// The fit's domain, refused outside: a viewer on the ground under a sun above the horizon.
/// It is Preetham's, with its own note: a fit to its own atmosphere (no ozone, one aerosol), reached
/// through the turbidity alone, so no AOD range either.
pub const DOMAIN: Domain = Domain {
    note: "Hosek and Wilkie's fit describes the daytime sky seen from the ground (turbidity 1–10, albedo 0–1, 320–720 nm)",
    ..super::preetham::DOMAIN
};

/// The spectral fit's band centres, nm.
pub const BAND_CENTRES_NM: [f64; 11] = [
    320.0, 360.0, 400.0, 440.0, 480.0, 520.0, 560.0, 600.0, 640.0, 680.0, 720.0,
];
/// Distance between band centres, nm.
pub const BAND_STEP_NM: f64 = 40.0;
/// Turbidities of the fit.
pub const TURBIDITY_RANGE: [f64; 2] = [1.0, 10.0];
/// The sun's angular radius in the solar radiance function, rad (0.51° / 2).
pub const SUN_RADIUS_RAD: f64 = 0.255 * PI / 180.0;
/// Cubic pieces of the solar radiance function over the solar elevation.
pub const SUN_PIECES: usize = 45;
/// Quadrature of the sky's irradiance on the ground: zenith-cosine and azimuth steps.
pub const GROUND_SKY_STEPS: [usize; 2] = [24, 24];

/// Rows of [`batch_rows`]: the lower band's A–I and L_M (× its weight), the upper band's, the
/// sun's transmittance and the ground's radiance.
pub const ROW_LOWER: usize = 0;
pub const ROW_UPPER: usize = 10;
pub const ROW_SUN: usize = 20;
pub const ROW_GROUND: usize = 21;

/// A channel's configuration: the distribution's coefficients in the tables' order A, B, C, D,
/// E, F, G, I, H, then the radiance scale L_M.
pub type Configuration = [f64; 10];

/// One channel of the fit (a spectral band or an sRGB primary): per ground albedo (0, 1),
/// turbidity (1–10) and Bézier control point (0–5), its configuration.
#[derive(Debug, Clone, PartialEq)]
pub struct Channel {
    pub points: [[[Configuration; 6]; 10]; 2],
}

/// The published fit.
#[derive(Debug, Clone, PartialEq)]
pub struct Data {
    /// The bands of [`BAND_CENTRES_NM`].
    pub spectral: Vec<Channel>,
    /// R, G, B (linear sRGB, in the unit Y = ∫ȳL dλ, W·m⁻²·sr⁻¹).
    pub rgb: Vec<Channel>,
    /// Per band and turbidity (1–10), the cubic pieces [c0, c1, c2, c3] of the radiance at the
    /// sun's centre, W·m⁻²·sr⁻¹·nm⁻¹.
    pub sun: Vec<[[[f64; 4]; SUN_PIECES]; 10]>,
    /// Per band, the limb darkening polynomial's coefficients d0–d5 in the cosine across the
    /// disk.
    pub limb: Vec<[f64; 6]>,
}

fn channels(t: &Table, column: &str, names: &[&str]) -> Vec<Channel> {
    let ids = t.text(column);
    let (albedo, turbidity, point) = (
        t.numbers("albedo"),
        t.numbers("turbidity"),
        t.numbers("control_point"),
    );
    let values: Vec<Vec<f64>> = ["A", "B", "C", "D", "E", "F", "G", "I", "H", "L_M"]
        .iter()
        .map(|c| t.numbers(c))
        .collect();
    names
        .iter()
        .map(|name| {
            let mut c = Channel {
                points: [[[[f64::NAN; 10]; 6]; 10]; 2],
            };
            for r in (0..t.len()).filter(|&r| ids[r] == *name) {
                let slot =
                    &mut c.points[albedo[r] as usize][turbidity[r] as usize - 1][point[r] as usize];
                for (k, v) in values.iter().enumerate() {
                    slot[k] = v[r];
                }
            }
            assert!(
                c.points
                    .iter()
                    .flatten()
                    .flatten()
                    .flatten()
                    .all(|v| v.is_finite()),
                "Hosek–Wilkie table lacks rows of {name}"
            );
            c
        })
        .collect()
}

impl Data {
    /// The tables embedded in `model/data`.
    pub fn published() -> &'static Data {
        static D: OnceLock<Data> = OnceLock::new();
        D.get_or_init(|| {
            let bands: Vec<String> = BAND_CENTRES_NM.iter().map(|b| format!("{b}")).collect();
            let band_names: Vec<&str> = bands.iter().map(String::as_str).collect();
            let s = tables::hosek_wilkie_sun();
            let (band, turbidity, piece) =
                (s.text("band"), s.numbers("turbidity"), s.numbers("piece"));
            let c: Vec<Vec<f64>> = ["c0", "c1", "c2", "c3"]
                .iter()
                .map(|n| s.numbers(n))
                .collect();
            let sun = band_names
                .iter()
                .map(|name| {
                    let mut pieces = [[[f64::NAN; 4]; SUN_PIECES]; 10];
                    for r in (0..s.len()).filter(|&r| band[r] == *name) {
                        pieces[turbidity[r] as usize - 1][piece[r] as usize] =
                            std::array::from_fn(|k| c[k][r]);
                    }
                    assert!(pieces.iter().flatten().flatten().all(|v| v.is_finite()));
                    pieces
                })
                .collect();
            let l = tables::hosek_wilkie_limb_darkening();
            let (lband, d): (Vec<&str>, Vec<Vec<f64>>) = (
                l.text("band"),
                ["d0", "d1", "d2", "d3", "d4", "d5"]
                    .iter()
                    .map(|n| l.numbers(n))
                    .collect(),
            );
            let limb = band_names
                .iter()
                .map(|name| {
                    let r = (0..l.len())
                        .find(|&r| lband[r] == *name)
                        .unwrap_or_else(|| panic!("limb darkening table lacks band {name}"));
                    std::array::from_fn(|k| d[k][r])
                })
                .collect();
            Data {
                spectral: channels(tables::hosek_wilkie_sky_spectral(), "band", &band_names),
                rgb: channels(tables::hosek_wilkie_sky_rgb(), "channel", &["R", "G", "B"]),
                sun,
                limb,
            }
        })
    }
}

/// The lower of the two integer turbidities a turbidity `t` (1–10) blends and the weight of
/// the upper: 10 is the upper end of 9–10.
fn turbidity_blend(t: f64) -> (usize, f64) {
    let t = t.clamp(TURBIDITY_RANGE[0], TURBIDITY_RANGE[1]);
    let lower = (t.floor() as usize).min(9);
    (lower, t - lower as f64)
}

/// x = (elevation / (π/2))^(1/3), the Bézier parameter of a solar elevation (rad, 0–π/2).
pub fn bezier_parameter(elevation: f64) -> f64 {
    (elevation.clamp(0.0, FRAC_PI_2) / FRAC_PI_2).cbrt()
}

/// A channel's configuration for turbidity `t` (1–10), ground albedo `albedo` (0–1) and solar
/// elevation `elevation` (rad, 0–π/2).
pub fn configuration(c: &Channel, t: f64, albedo: f64, elevation: f64) -> Configuration {
    let x = bezier_parameter(elevation);
    let binomial = [1.0, 5.0, 10.0, 10.0, 5.0, 1.0];
    let bernstein: [f64; 6] =
        std::array::from_fn(|k| binomial[k] * x.powi(k as i32) * (1.0 - x).powi(5 - k as i32));
    let (lower, upper_weight) = turbidity_blend(t);
    let albedo = albedo.clamp(0.0, 1.0);
    let mut out = [0.0; 10];
    for (a, wa) in [(0, 1.0 - albedo), (1, albedo)] {
        for (turbidity, wt) in [(lower - 1, 1.0 - upper_weight), (lower, upper_weight)] {
            let w = wa * wt;
            if w == 0.0 {
                continue;
            }
            for (k, b) in bernstein.iter().enumerate() {
                for (o, v) in out.iter_mut().zip(&c.points[a][turbidity][k]) {
                    *o += w * b * v;
                }
            }
        }
    }
    out
}

/// The distribution F(θ, γ) of a configuration (its first nine numbers) along a direction of
/// zenith cosine `cos_theta` (held to 0 or more) at angle `gamma` (rad) from the sun.
pub fn distribution(c: &Configuration, cos_theta: f64, gamma: f64) -> f64 {
    let [a, b, cc, d, e, f, g, i, h] = [c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7], c[8]];
    let cos_theta = cos_theta.max(0.0);
    let cos_gamma = gamma.cos();
    let chi = (1.0 + cos_gamma * cos_gamma) / (1.0 + h * h - 2.0 * h * cos_gamma).powf(1.5);
    (1.0 + a * (b / (cos_theta + 0.01)).exp())
        * (cc + d * (e * gamma).exp() + f * cos_gamma * cos_gamma + g * chi + i * cos_theta.sqrt())
}

/// The radiance at the sun's centre in band `band` for turbidity `t` (1–10) with the sun at
/// `elevation` (rad), W·m⁻²·sr⁻¹·nm⁻¹; 0 below the horizon.
pub fn sun_centre_radiance(band: usize, t: f64, elevation: f64) -> f64 {
    if elevation < 0.0 {
        return 0.0;
    }
    let d = Data::published();
    let elevation = elevation.min(FRAC_PI_2);
    let piece = ((bezier_parameter(elevation) * SUN_PIECES as f64) as usize).min(SUN_PIECES - 1);
    let start = (piece as f64 / SUN_PIECES as f64).powi(3) * FRAC_PI_2;
    let u = elevation - start;
    let at = |turbidity: usize| {
        let [c0, c1, c2, c3] = d.sun[band][turbidity][piece];
        c0 + u * (c1 + u * (c2 + u * c3))
    };
    let (lower, w) = turbidity_blend(t);
    (1.0 - w) * at(lower - 1) + w * at(lower)
}

/// The mean over the sun's disk of band `band`'s limb darkening (1 at the centre): the mean of
/// Σ d_k s^k, s the cosine across the disk, is Σ d_k · 2 / (k + 2).
pub fn mean_limb_darkening(band: usize) -> f64 {
    Data::published().limb[band]
        .iter()
        .enumerate()
        .map(|(k, d)| d * 2.0 / (k as f64 + 2.0))
        .sum()
}

/// How a lane at `wavelength_nm` blends the bands: the lower band and the weights of the
/// lower and upper. Between 320 and 720 nm linearly; outside, the nearest end band times the
/// ratio of the solar irradiance there to that at the band's centre (same band width).
fn band_blend(wavelength_nm: f64, band_width_nm: f64) -> (usize, f64, f64) {
    let first = BAND_CENTRES_NM[0];
    let last = BAND_CENTRES_NM[BAND_CENTRES_NM.len() - 1];
    let solar = |l: f64| SolarSpectrum::default().irradiance(l, band_width_nm);
    if wavelength_nm > last {
        (
            BAND_CENTRES_NM.len() - 2,
            0.0,
            solar(wavelength_nm) / solar(last),
        )
    } else if wavelength_nm < first {
        (0, solar(wavelength_nm) / solar(first), 0.0)
    } else {
        let f = (wavelength_nm - first) / BAND_STEP_NM;
        let lower = (f.floor() as usize).min(BAND_CENTRES_NM.len() - 2);
        let w = f - lower as f64;
        (lower, 1.0 - w, w)
    }
}

/// The sky's irradiance on a horizontal plane from a channel's configuration `c` with the sun
/// at zenith cosine `mu_s`, in the unit of L_M: ∫ F·cos θ dω over the upper hemisphere times
/// L_M ([`GROUND_SKY_STEPS`]).
pub fn sky_irradiance(c: &Configuration, mu_s: f64) -> f64 {
    hemisphere_irradiance(mu_s, GROUND_SKY_STEPS, |mu, gamma| {
        distribution(c, mu, gamma)
    }) * c[9]
}

/// Whether `b` is RGB3's batch, whose lanes 0–2 are R, G, B read with weights ∫ȳ dλ.
fn rgb3_weights(b: &crate::wavelengths::WavelengthBatch) -> Option<[f64; 3]> {
    let rgb = crate::wavelengths::RGB3_NM;
    let diagonal = (0..3).all(|r| (0..LANES).all(|l| (b.to_srgb[r][l] != 0.0) == (r == l)));
    (b.wavelengths_nm[..3] == rgb && diagonal).then(|| std::array::from_fn(|r| b.to_srgb[r][r]))
}

/// Everything the sky pass reads for batch `layer` of `p` with the sun at zenith cosine `mu_s`
/// ([`ROW_LOWER`], [`ROW_UPPER`], [`ROW_SUN`], [`ROW_GROUND`]), per lane: the configurations of
/// the two bands around the lane (each L_M times the band's weight; RGB3's lanes 0–2 the sRGB
/// fit's channel, in lane units), the sun's transmittance (the fit's disk irradiance over the
/// reference extraterrestrial irradiance, per band) and the radiance of the Lambertian ground under the
/// fit's sun and sky. All of it scales with the lane's solar irradiance over the default
/// spectrum's at 1 AU, so the fit follows the scene's sun (its spectrum and distance) as every
/// model does.
pub fn batch_rows(p: &Params, layer: usize, mu_s: f64) -> BatchRows {
    let d = Data::published();
    let t = turbidity(p);
    let elevation = mu_s.clamp(-1.0, 1.0).asin();
    let b = &p.batches[layer];
    let rgb = rgb3_weights(&b.colour);
    let band_width_nm = b.colour.bandwidth_nm.unwrap_or(POINT_SET_SOLAR_BAND_NM);
    let sun_solid_angle = PI * SUN_RADIUS_RAD.sin().powi(2);
    let mut rows = [Lanes::ZERO; super::shared::BATCH_MODEL_ROWS];
    for lane in 0..LANES {
        let albedo = b.ground_albedo[lane].clamp(0.0, 1.0);
        let wavelength = b.colour.wavelengths_nm[lane];
        let (lower, w_lower, w_upper) = band_blend(wavelength, band_width_nm);
        let (mut low, mut high) = match rgb.filter(|_| lane < 3) {
            Some(weights) => {
                let mut c = configuration(&d.rgb[lane], t, albedo, elevation);
                c[9] /= weights[lane];
                (c, [0.0; 10])
            }
            None => (
                configuration(&d.spectral[lower], t, albedo, elevation),
                configuration(&d.spectral[lower + 1], t, albedo, elevation),
            ),
        };
        if rgb.is_none() || lane >= 3 {
            low[9] *= w_lower;
            high[9] *= w_upper;
        }
        // The fit's light is its own sun's at 1 AU: under the scene's sun (another spectrum,
        // another distance) it scales with the lane's irradiance over the reference spectrum's.
        let extraterrestrial = b.solar_irradiance[lane];
        let reference = SolarSpectrum::default().irradiance(wavelength, band_width_nm);
        let sun_scale = if reference > 0.0 {
            extraterrestrial / reference
        } else {
            0.0
        };
        low[9] *= sun_scale;
        high[9] *= sun_scale;
        for k in 0..10 {
            rows[ROW_LOWER + k][lane] = low[k];
            rows[ROW_UPPER + k][lane] = high[k];
        }
        // The sun's transmittance, each band's disk irradiance over the reference spectrum
        // averaged over the band, interpolated between the bands around the lane (the end
        // band's outside 320–720 nm, where the transmittance is nearly flat).
        let band_transmittance = |band: usize| {
            let disk = sun_centre_radiance(band, t, elevation)
                * mean_limb_darkening(band)
                * sun_solid_angle;
            let e = SolarSpectrum::default().irradiance(BAND_CENTRES_NM[band], BAND_STEP_NM);
            if e > 0.0 { disk / e } else { 0.0 }
        };
        let f = (wavelength - BAND_CENTRES_NM[0]) / BAND_STEP_NM;
        let w = (f - lower as f64).clamp(0.0, 1.0);
        let transmittance =
            (1.0 - w) * band_transmittance(lower) + w * band_transmittance(lower + 1);
        rows[ROW_SUN][lane] = transmittance;
        let direct = extraterrestrial * transmittance * mu_s.max(0.0);
        let sky = sky_irradiance(&low, mu_s) + sky_irradiance(&high, mu_s);
        rows[ROW_GROUND][lane] = albedo / PI * (direct + sky);
    }
    rows
}

/// The scene's turbidity (`OpticalDepth::turbidity`), held to 1–10.
pub fn turbidity(p: &Params) -> f64 {
    p.optical_depth_550.turbidity(TURBIDITY_RANGE)
}

/// The registry's constructor: the twin of the sky pass over [`batch_rows`].
pub fn build(params: &Params, _: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(RowSky::new(
        params,
        batch_rows,
        sky::radiance,
        ROW_SUN,
        turbidity(params),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Method, Scene, WavelengthSet};

    fn band(nm: f64) -> usize {
        BAND_CENTRES_NM
            .iter()
            .position(|&b| b == nm)
            .expect("a band centre")
    }

    fn radiance(
        c: &Channel,
        t: f64,
        albedo: f64,
        elevation_deg: f64,
        theta_deg: f64,
        gamma_deg: f64,
    ) -> f64 {
        let c = configuration(c, t, albedo, elevation_deg.to_radians());
        distribution(&c, theta_deg.to_radians().cos(), gamma_deg.to_radians()) * c[9]
    }

    /// Values worked out apart from this code, from the CSV tables and the formula of the
    /// module's documentation (a separate script: Bézier weights C(5,k)·x^k·(1−x)^(5−k) with
    /// x = (elevation/90°)^(1/3), linear in turbidity and albedo). They are the output of
    /// `tests/scripts/hosek_wilkie_golden_values.py` (`python3` from the repository root):
    /// - 560 nm, T = 3, albedo 0, sun at the zenith (x = 1: the last control point alone),
    ///   looking at the zenith (θ = γ = 0): 0.133330 W·m⁻²·sr⁻¹·nm⁻¹;
    /// - 440 nm, T = 2.5, albedo 0.5, sun 11.25° up (x = 1/2: all six points), θ = 60°,
    ///   γ = 90°: 0.0663070;
    /// - the sRGB fit's G, T = 10 (the upper end), albedo 1, sun 45° up, θ = 30°, γ = 20°:
    ///   58.5171 (W·m⁻²·sr⁻¹, Y-weighted);
    /// - 580 nm, halfway between the 560 and 600 nm bands, T = 4, albedo 0.3, sun 30° up, at the
    ///   zenith (γ = 60°): 0.0283864;
    /// - the sun's centre at 560 nm, T = 3, 30° up: 18 982.3 W·m⁻²·sr⁻¹·nm⁻¹ (piece 32 of 45);
    ///   at 440 nm, T = 2.5, 5° up: 977.914.
    #[test]
    fn the_fit_gives_the_values_worked_out_from_its_tables() {
        let d = Data::published();
        let close = |got: f64, want: f64| {
            assert!((got / want - 1.0).abs() < 1e-5, "{got} vs {want}");
        };
        close(
            radiance(&d.spectral[band(560.0)], 3.0, 0.0, 90.0, 0.0, 0.0),
            0.133330,
        );
        close(
            radiance(&d.spectral[band(440.0)], 2.5, 0.5, 11.25, 60.0, 90.0),
            0.0663070,
        );
        close(radiance(&d.rgb[1], 10.0, 1.0, 45.0, 30.0, 20.0), 58.5171);
        let between = 0.5 * radiance(&d.spectral[band(560.0)], 4.0, 0.3, 30.0, 0.0, 60.0)
            + 0.5 * radiance(&d.spectral[band(600.0)], 4.0, 0.3, 30.0, 0.0, 60.0);
        close(between, 0.0283864);
        close(
            sun_centre_radiance(band(560.0), 3.0, 30f64.to_radians()),
            18_982.3,
        );
        close(
            sun_centre_radiance(band(440.0), 2.5, 5f64.to_radians()),
            977.914,
        );
    }

    /// The solar radiance function's pieces join: each piece's value at the next one's start
    /// is that piece's first coefficient (within 0.1 %), so the sun brightens smoothly.
    #[test]
    fn the_suns_pieces_join() {
        for b in 0..BAND_CENTRES_NM.len() {
            for t in 1..=10 {
                for piece in 1..SUN_PIECES {
                    let start = (piece as f64 / SUN_PIECES as f64).powi(3) * FRAC_PI_2;
                    let before = sun_centre_radiance(b, t as f64, start - 1e-12);
                    let after = sun_centre_radiance(b, t as f64, start + 1e-12);
                    assert!(
                        (before - after).abs() <= 1e-3 * after.abs().max(1.0),
                        "band {b} T {t} piece {piece}: {before} vs {after}"
                    );
                }
            }
        }
    }

    /// The limb darkening is 1 at the disk's centre in every band (to the tables' digits),
    /// and its mean over the disk lies between the edge's value and 1.
    #[test]
    fn the_limb_darkening_is_one_at_the_centre() {
        for b in 0..BAND_CENTRES_NM.len() {
            let d = Data::published().limb[b];
            // The published coefficients have six digits: their sum is 1 within 2e-3.
            assert!((d.iter().sum::<f64>() - 1.0).abs() < 2e-3, "{d:?}");
            let mean = mean_limb_darkening(b);
            assert!(d[0] < mean && mean < 1.0, "band {b}: {mean}");
        }
    }

    /// The sRGB fit and the spectral fit agree on the sky's colour: the spectral sky
    /// integrated against the colour matching functions (SpectralN) is within 6 % of the sRGB
    /// fit per channel over a hazy and a clear sky, so RGB3 and the spectral sets show one sky.
    #[test]
    fn the_rgb_fit_is_the_spectral_fit_in_srgb() {
        for (aod, elevation) in [(0.05, 30.0), (0.3, 60.0)] {
            let mut s = Scene::default();
            s.atmosphere.aerosol.aod550 = aod;
            let atm = crate::atmosphere::Atmosphere::for_scene(&s);
            let srgb = |set: WavelengthSet| {
                let p = Params::new(&atm, set, crate::scene::Quality::Low);
                let mu_s = f64::sin(f64::to_radians(elevation));
                let mut rgb = [0.0; 3];
                for layer in 0..p.batches.len() {
                    let rows = batch_rows(&p, layer, mu_s);
                    // 40° up, 70° from the sun.
                    let (mu, nu) = (40f64.to_radians().sin(), 70f64.to_radians().cos());
                    let l = sky::sky(&rows, mu, nu);
                    for (r, row) in p.batches[layer].colour.to_srgb.iter().enumerate() {
                        rgb[r] += (0..LANES).map(|i| row[i] * l[i]).sum::<f64>();
                    }
                }
                rgb
            };
            let (fit, spectral) = (
                srgb(WavelengthSet::Rgb3),
                srgb(WavelengthSet::SpectralN(48)),
            );
            for r in 0..3 {
                assert!(
                    (fit[r] / spectral[r] - 1.0).abs() < 0.06,
                    "AOD {aod}: {fit:?} vs {spectral:?}"
                );
            }
        }
    }

    /// The turbidity is Preetham's ratio held to 1–10; the probe's model reports it.
    #[test]
    fn the_turbidity_is_the_ratio_of_optical_depths_held_to_the_fit() {
        let mut s = Scene::default();
        s.render.method = Method::HosekWilkie;
        s.atmosphere.aerosol.aod550 = 0.2;
        let atm = crate::atmosphere::Atmosphere::for_scene(&s);
        let p = Params::new(&atm, WavelengthSet::Spectral4, crate::scene::Quality::Low);
        let tau = p.optical_depth_550;
        let t = turbidity(&p);
        assert!((t - (1.0 + tau.aerosol / tau.rayleigh)).abs() < 1e-12);
        let model = build(&p, Viewpoint { h: 1.0, mu_s: 0.5 });
        assert_eq!(model.turbidity(), Some(t));
        s.atmosphere.aerosol.aod550 = 3.0;
        let atm = crate::atmosphere::Atmosphere::for_scene(&s);
        let p = Params::new(&atm, WavelengthSet::Spectral4, crate::scene::Quality::Low);
        assert_eq!(turbidity(&p), 10.0);
    }

    /// The sun's transmittance lies in (0, 1] at every lane of a fine spectral set, inside the
    /// fit's bands and past them (SpectralN reaches 830 nm), with the sun high and low, and it
    /// grows towards the red.
    #[test]
    fn the_suns_transmittance_is_a_transmittance_at_every_wavelength() {
        let s = Scene::default();
        let atm = crate::atmosphere::Atmosphere::for_scene(&s);
        let p = Params::new(
            &atm,
            WavelengthSet::SpectralN(96),
            crate::scene::Quality::Low,
        );
        for elevation_deg in [90.0, 30.0, 5.0] {
            let mu_s = f64::sin(f64::to_radians(elevation_deg));
            let mut last = 0.0;
            for layer in 0..p.batches.len() {
                let rows = batch_rows(&p, layer, mu_s);
                for lane in 0..LANES {
                    let t = rows[ROW_SUN][lane];
                    let nm = p.batches[layer].colour.wavelengths_nm[lane];
                    assert!(t > 0.0 && t <= 1.0, "sun {elevation_deg}°, {nm} nm: {t}");
                    assert!(
                        t >= 0.98 * last,
                        "sun {elevation_deg}°, {nm} nm: {t} after {last}"
                    );
                    last = t;
                }
            }
        }
    }

    /// The ground under the fit's sun and sky: brighter with a higher sun, and its radiance
    /// the albedo over π times the direct and diffuse irradiance (sky between 10 % and 60 %
    /// of the total in the green at sun 30°, as clear skies give).
    #[test]
    fn the_ground_is_lit_by_the_fits_sun_and_sky() {
        let s = Scene::default();
        let atm = crate::atmosphere::Atmosphere::for_scene(&s);
        let p = Params::new(&atm, WavelengthSet::Spectral4, crate::scene::Quality::Low);
        let low = batch_rows(&p, 0, 10f64.to_radians().sin());
        let high = batch_rows(&p, 0, 30f64.to_radians().sin());
        for lane in 0..LANES {
            assert!(high[ROW_GROUND][lane] > low[ROW_GROUND][lane] && low[ROW_GROUND][lane] > 0.0);
        }
        let b = &p.batches[0];
        let green = (0..LANES)
            .min_by(|&a, &c| {
                (b.colour.wavelengths_nm[a] - 550.0)
                    .abs()
                    .total_cmp(&(b.colour.wavelengths_nm[c] - 550.0).abs())
            })
            .expect("four lanes");
        let direct = b.solar_irradiance[green] * high[ROW_SUN][green] * 0.5;
        let total = high[ROW_GROUND][green] * PI / b.ground_albedo[green];
        let sky_share = 1.0 - direct / total;
        assert!((0.1..0.6).contains(&sky_share), "{sky_share}");
        assert!(
            (0.3..1.0).contains(&high[ROW_SUN][green]),
            "{:?}",
            high[ROW_SUN]
        );
    }
}
