//! Vertical profiles of air and ozone number density.
//!
//! Air: the US Standard Atmosphere 1976 table (geopotential levels converted to geometric
//! altitude; continued above 86 km by the AFGL US-standard profile), any of the six AFGL 1986
//! profiles (Anderson et al. 1986), the fit n(h) = n₀·exp(−a·h^b) of García Liñán (2023), or
//! the real-time literature's pure exponential with an 8 km scale height (Bruneton & Neyret
//! 2008, Hillaire 2020). Ozone: the AFGL profiles, the Guimera et al. (2018) 9 km layers,
//! García Liñán's smooth log-normal fit, or Bruneton's (2017) tent from 10 to 40 km, each
//! scaled to a total column. Tables are interpolated linearly in ln(n)
//! against altitude, exact for an exponential between levels.

use crate::constants::{
    AIR_DENSITY_FIT_A, AIR_DENSITY_FIT_B, DOBSON_UNIT_PER_M2, EXPONENTIAL_AIR_SCALE_HEIGHT_M,
    OZONE_FIT_C, OZONE_FIT_K, OZONE_TENT_HALF_WIDTH_M, OZONE_TENT_PEAK_M,
};
use crate::csv_table::tables;
use crate::quadrature::integrate_adaptive;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// The six AFGL 1986 standard atmospheres.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum AfglProfile {
    UsStandard,
    Tropical,
    MidlatitudeSummer,
    MidlatitudeWinter,
    SubarcticSummer,
    SubarcticWinter,
}

impl AfglProfile {
    pub const ALL: [AfglProfile; 6] = [
        AfglProfile::UsStandard,
        AfglProfile::Tropical,
        AfglProfile::MidlatitudeSummer,
        AfglProfile::MidlatitudeWinter,
        AfglProfile::SubarcticSummer,
        AfglProfile::SubarcticWinter,
    ];

    /// Name of the profile in the AFGL table.
    fn table_key(self) -> &'static str {
        match self {
            AfglProfile::UsStandard => "us_standard",
            AfglProfile::Tropical => "tropical",
            AfglProfile::MidlatitudeSummer => "midlatitude_summer",
            AfglProfile::MidlatitudeWinter => "midlatitude_winter",
            AfglProfile::SubarcticSummer => "subarctic_summer",
            AfglProfile::SubarcticWinter => "subarctic_winter",
        }
    }

    /// The command-line name, e.g. `afgl-tropical`.
    pub fn cli_name(self) -> &'static str {
        match self {
            AfglProfile::UsStandard => "afgl-us-standard",
            AfglProfile::Tropical => "afgl-tropical",
            AfglProfile::MidlatitudeSummer => "afgl-midlatitude-summer",
            AfglProfile::MidlatitudeWinter => "afgl-midlatitude-winter",
            AfglProfile::SubarcticSummer => "afgl-subarctic-summer",
            AfglProfile::SubarcticWinter => "afgl-subarctic-winter",
        }
    }

    fn index(self) -> usize {
        AfglProfile::ALL
            .iter()
            .position(|&p| p == self)
            .unwrap_or(0)
    }
}

/// Where the air density comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum AirProfile {
    /// US Standard Atmosphere 1976 (table, 1 km levels to 86 km, AFGL above).
    #[default]
    UsStandard1976,
    /// One of the AFGL 1986 profiles.
    Afgl(AfglProfile),
    /// n₀·exp(−a·h^b) with a = 0.07771971, b = 1.16364243, h in km (García Liñán 2023).
    ExponentialFit,
    /// n₀·exp(−h/8 km): the air of Bruneton & Neyret (2008) and Hillaire (2020), with the US
    /// Standard Atmosphere's ground density.
    Exponential8km,
}

impl AirProfile {
    /// Every choice with its command-line name.
    pub fn all() -> Vec<AirProfile> {
        let mut v = vec![AirProfile::UsStandard1976];
        v.extend(AfglProfile::ALL.map(AirProfile::Afgl));
        v.push(AirProfile::ExponentialFit);
        v.push(AirProfile::Exponential8km);
        v
    }

    pub fn cli_name(self) -> &'static str {
        match self {
            AirProfile::UsStandard1976 => "us-standard-1976",
            AirProfile::Afgl(p) => p.cli_name(),
            AirProfile::ExponentialFit => "exponential-fit",
            AirProfile::Exponential8km => "exponential-8km",
        }
    }

    pub fn from_cli_name(name: &str) -> Option<AirProfile> {
        AirProfile::all().into_iter().find(|p| p.cli_name() == name)
    }

    /// Air number density at geometric altitude `h_m` (m), molecules·m⁻³. Below the ground the
    /// ground value holds; above the table's top the last level's scale height continues.
    pub fn number_density_m3(self, h_m: f64) -> f64 {
        match self {
            AirProfile::UsStandard1976 => us_standard_air().eval(h_m),
            AirProfile::Afgl(p) => afgl_levels()[p.index()].air.eval(h_m),
            AirProfile::ExponentialFit => {
                let h_km = (h_m / 1000.0).max(0.0);
                us_standard_air().eval(0.0)
                    * (-AIR_DENSITY_FIT_A * h_km.powf(AIR_DENSITY_FIT_B)).exp()
            }
            AirProfile::Exponential8km => {
                us_standard_air().eval(0.0) * (-h_m.max(0.0) / EXPONENTIAL_AIR_SCALE_HEIGHT_M).exp()
            }
        }
    }

    /// Altitudes (m) where the profile's derivative jumps; quadrature splits there.
    pub fn breakpoints_m(self) -> &'static [f64] {
        match self {
            AirProfile::UsStandard1976 => &us_standard_air().z_m,
            AirProfile::Afgl(p) => &afgl_levels()[p.index()].air.z_m,
            AirProfile::ExponentialFit | AirProfile::Exponential8km => &[],
        }
    }
}

/// The vertical shape of the ozone layer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum OzoneProfile {
    /// The ozone of an AFGL 1986 profile (its own column unless a column is given).
    Afgl(AfglProfile),
    /// Guimera et al. (2018): six 9 km layers of constant density, zero above 54 km.
    Guimera,
    /// García Liñán (2023): n ∝ exp(−k·(ln h − c)²)/h, h in km, peak near 20 km.
    #[default]
    Fit,
    /// Bruneton (2017) and Hillaire (2020): a tent rising linearly from 10 km to its peak at
    /// 25 km and falling to zero at 40 km.
    Tent,
}

impl OzoneProfile {
    pub fn all() -> Vec<OzoneProfile> {
        let mut v: Vec<_> = AfglProfile::ALL.map(OzoneProfile::Afgl).to_vec();
        v.push(OzoneProfile::Guimera);
        v.push(OzoneProfile::Fit);
        v.push(OzoneProfile::Tent);
        v
    }

    pub fn cli_name(self) -> &'static str {
        match self {
            OzoneProfile::Afgl(p) => p.cli_name(),
            OzoneProfile::Guimera => "guimera",
            OzoneProfile::Fit => "fit",
            OzoneProfile::Tent => "tent",
        }
    }

    pub fn from_cli_name(name: &str) -> Option<OzoneProfile> {
        OzoneProfile::all()
            .into_iter()
            .find(|p| p.cli_name() == name)
    }

    /// Unnormalised shape at `h_m`, m⁻³ for AFGL (its own density), arbitrary scale otherwise.
    fn shape(self, h_m: f64) -> f64 {
        match self {
            OzoneProfile::Afgl(p) => afgl_levels()[p.index()].ozone.eval(h_m),
            OzoneProfile::Guimera => {
                let layers = guimera_layers();
                layers
                    .iter()
                    .find(|l| h_m >= l.0 && h_m < l.1)
                    .map_or(0.0, |l| l.2)
            }
            OzoneProfile::Fit => {
                let h_km = h_m / 1000.0;
                if h_km <= 0.0 {
                    return 0.0;
                }
                (-OZONE_FIT_K * (h_km.ln() - OZONE_FIT_C).powi(2)).exp() / h_km
            }
            OzoneProfile::Tent => {
                (1.0 - (h_m - OZONE_TENT_PEAK_M).abs() / OZONE_TENT_HALF_WIDTH_M).max(0.0)
            }
        }
    }

    fn breakpoints_m(self) -> Vec<f64> {
        match self {
            OzoneProfile::Afgl(p) => afgl_levels()[p.index()].ozone.z_m.clone(),
            OzoneProfile::Guimera => guimera_layers().iter().flat_map(|l| [l.0, l.1]).collect(),
            OzoneProfile::Fit => vec![],
            OzoneProfile::Tent => vec![
                OZONE_TENT_PEAK_M - OZONE_TENT_HALF_WIDTH_M,
                OZONE_TENT_PEAK_M,
                OZONE_TENT_PEAK_M + OZONE_TENT_HALF_WIDTH_M,
            ],
        }
    }

    /// ∫ shape dh from the ground to `top_m`, in the shape's unit × m.
    fn shape_column(self, top_m: f64) -> f64 {
        let mut cuts: Vec<f64> = std::iter::once(0.0)
            .chain(
                self.breakpoints_m()
                    .into_iter()
                    .filter(|&z| z > 0.0 && z < top_m),
            )
            .chain(std::iter::once(top_m))
            .collect();
        cuts.dedup();
        cuts.windows(2)
            .map(|w| integrate_adaptive(|h| self.shape(h), w[0], w[1], 1e-10, 0.0).value)
            .sum()
    }

    /// The column (DU) the profile carries by itself between the ground and `top_m`, for
    /// profiles that have one (AFGL).
    pub fn native_column_du(self, top_m: f64) -> Option<f64> {
        match self {
            OzoneProfile::Afgl(_) => Some(self.shape_column(top_m) / DOBSON_UNIT_PER_M2),
            _ => None,
        }
    }

    /// A profile scaled so that its vertical column between the ground and `top_m` is
    /// `column_du` Dobson units.
    pub fn scaled(self, column_du: f64, top_m: f64) -> ScaledOzone {
        let column = self.shape_column(top_m);
        let scale = if column > 0.0 {
            column_du * DOBSON_UNIT_PER_M2 / column
        } else {
            0.0
        };
        ScaledOzone {
            profile: self,
            scale,
            breakpoints_m: self.breakpoints_m(),
        }
    }
}

/// An ozone profile in absolute number density.
#[derive(Debug, Clone)]
pub struct ScaledOzone {
    profile: OzoneProfile,
    scale: f64,
    breakpoints_m: Vec<f64>,
}

impl ScaledOzone {
    /// Ozone number density at altitude `h_m`, molecules·m⁻³.
    pub fn number_density_m3(&self, h_m: f64) -> f64 {
        self.scale * self.profile.shape(h_m)
    }

    pub fn breakpoints_m(&self) -> &[f64] {
        &self.breakpoints_m
    }
}

/// A tabulated profile interpolated linearly in ln(n).
#[derive(Debug, Clone)]
struct LogTable {
    z_m: Vec<f64>,
    ln_n: Vec<f64>,
}

impl LogTable {
    fn new(z_m: Vec<f64>, n: Vec<f64>) -> LogTable {
        // Tiny floor keeps ln finite for levels that list zero.
        let ln_n = n.iter().map(|&v| v.max(1e-30).ln()).collect();
        LogTable { z_m, ln_n }
    }

    fn eval(&self, h_m: f64) -> f64 {
        let z = &self.z_m;
        let last = z.len() - 1;
        let i = z.partition_point(|&x| x <= h_m).clamp(1, last);
        let h = h_m.max(z[0]);
        let t = (h - z[i - 1]) / (z[i] - z[i - 1]);
        (self.ln_n[i - 1] + t * (self.ln_n[i] - self.ln_n[i - 1])).exp()
    }
}

struct AfglLevels {
    air: LogTable,
    ozone: LogTable,
}

fn afgl_levels() -> &'static [AfglLevels] {
    static LEVELS: OnceLock<Vec<AfglLevels>> = OnceLock::new();
    LEVELS.get_or_init(|| {
        AfglProfile::ALL
            .iter()
            .map(|p| {
                let t = tables::afgl1986().filter("profile", p.table_key());
                let z_m: Vec<f64> = t.numbers("z_km").iter().map(|z| z * 1000.0).collect();
                let cm3_to_m3 = |v: Vec<f64>| v.into_iter().map(|x| x * 1e6).collect::<Vec<_>>();
                AfglLevels {
                    air: LogTable::new(z_m.clone(), cm3_to_m3(t.numbers("air_cm3"))),
                    ozone: LogTable::new(z_m, cm3_to_m3(t.numbers("o3_cm3"))),
                }
            })
            .collect()
    })
}

/// USSA 1976 air to 86 km, continued with the AFGL US-standard levels above.
fn us_standard_air() -> &'static LogTable {
    static TABLE: OnceLock<LogTable> = OnceLock::new();
    TABLE.get_or_init(|| {
        let t = tables::us_standard_1976();
        let mut z_m: Vec<f64> = t
            .numbers("z_geometric_km")
            .iter()
            .map(|z| z * 1000.0)
            .collect();
        let mut n = t.numbers("n_air_m3");
        let top = *z_m.last().unwrap_or(&0.0);
        let afgl = &afgl_levels()[AfglProfile::UsStandard.index()].air;
        for (&z, &ln) in afgl.z_m.iter().zip(&afgl.ln_n) {
            if z > top + 1.0 {
                z_m.push(z);
                n.push(ln.exp());
            }
        }
        LogTable::new(z_m, n)
    })
}

/// Guimera layers as (bottom m, top m, shape value ∝ fraction per km).
fn guimera_layers() -> &'static [(f64, f64, f64)] {
    static LAYERS: OnceLock<Vec<(f64, f64, f64)>> = OnceLock::new();
    LAYERS.get_or_init(|| {
        let t = tables::ozone_guimera_layers();
        let b = t.numbers("z_bottom_km");
        let top = t.numbers("z_top_km");
        let f = t.numbers("fraction_per_km");
        (0..t.len())
            .map(|i| (b[i] * 1000.0, top[i] * 1000.0, f[i]))
            .collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sea_level_air_density_matches_standard_air() {
        let n0 = AirProfile::UsStandard1976.number_density_m3(0.0);
        assert!((n0 / 2.54692e25 - 1.0).abs() < 1e-5);
        let n_fit = AirProfile::ExponentialFit.number_density_m3(0.0);
        assert_eq!(n0, n_fit);
        for p in AfglProfile::ALL {
            let n = AirProfile::Afgl(p).number_density_m3(0.0);
            assert!(n > 2.3e25 && n < 3.0e25, "{p:?}: {n}");
        }
    }

    #[test]
    fn air_density_falls_monotonically_with_altitude() {
        for p in AirProfile::all() {
            let mut prev = f64::INFINITY;
            for k in 0..=120 {
                let n = p.number_density_m3(k as f64 * 1000.0);
                assert!(n > 0.0 && n < prev, "{p:?} at {k} km: {n}");
                prev = n;
            }
        }
    }

    /// The literature's Earth: air e-folds over 8 km exactly, ozone is a tent whose column
    /// is its peak density times 15 km (Bruneton's 300 DU over 15 km peak).
    #[test]
    fn the_exponential_air_and_the_ozone_tent_have_their_stated_shapes() {
        let p = AirProfile::Exponential8km;
        let ratio = p.number_density_m3(0.0) / p.number_density_m3(8_000.0);
        assert!((ratio - std::f64::consts::E).abs() < 1e-12, "{ratio}");
        let o = OzoneProfile::Tent.scaled(300.0, 100_000.0);
        let peak = o.number_density_m3(25_000.0);
        assert!((peak * 15_000.0 / (300.0 * DOBSON_UNIT_PER_M2) - 1.0).abs() < 1e-9);
        assert!((o.number_density_m3(17_500.0) / peak - 0.5).abs() < 1e-12);
        assert_eq!(o.number_density_m3(9_000.0), 0.0);
        assert_eq!(o.number_density_m3(41_000.0), 0.0);
    }

    #[test]
    fn ussa_scale_height_near_ground_is_about_8_km() {
        let p = AirProfile::UsStandard1976;
        let h = 1000.0 / (p.number_density_m3(0.0) / p.number_density_m3(1000.0)).ln();
        assert!(h > 8_000.0 && h < 10_500.0, "{h}");
    }

    #[test]
    fn ozone_profiles_scale_to_the_requested_column() {
        for p in OzoneProfile::all() {
            let s = p.scaled(300.0, 100_000.0);
            let col =
                integrate_adaptive(|h| s.number_density_m3(h), 0.0, 100_000.0, 1e-9, 0.0).value;
            assert!(
                (col / (300.0 * DOBSON_UNIT_PER_M2) - 1.0).abs() < 1e-3,
                "{p:?}: {col}"
            );
        }
    }

    #[test]
    fn afgl_native_ozone_columns_are_plausible() {
        for p in AfglProfile::ALL {
            let du = OzoneProfile::Afgl(p).native_column_du(120_000.0).unwrap();
            assert!(du > 250.0 && du < 500.0, "{p:?}: {du} DU");
        }
    }

    #[test]
    fn ozone_peaks_in_the_stratosphere() {
        for p in OzoneProfile::all() {
            let s = p.scaled(300.0, 100_000.0);
            let peak = (0..60).max_by(|&a, &b| {
                s.number_density_m3(a as f64 * 1000.0 + 500.0)
                    .total_cmp(&s.number_density_m3(b as f64 * 1000.0 + 500.0))
            });
            let peak_km = peak.unwrap();
            assert!((15..=30).contains(&peak_km), "{p:?} peaks at {peak_km} km");
        }
    }

    #[test]
    fn profile_names_round_trip() {
        for p in AirProfile::all() {
            assert_eq!(AirProfile::from_cli_name(p.cli_name()), Some(p));
        }
        for p in OzoneProfile::all() {
            assert_eq!(OzoneProfile::from_cli_name(p.cli_name()), Some(p));
        }
    }
}
