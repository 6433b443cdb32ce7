//! Ozone absorption: cross-sections and the monthly total column.
//!
//! Bogumil et al. (2003) give σ(λ, T) = (C₀ + C₁·ΔT + C₂·ΔT²)·10⁻²⁰ cm², ΔT = T − 273.15 K,
//! valid for about 203–293 K (the ozone layer is near 220–240 K). Serdyuchenko/Gorshelev et al.
//! (2014) at 233 K in 10 nm bins is the set Bruneton (2017) uses. Monthly columns are the Arosa
//! means of Dütsch (1973) used by Guimera et al. (2018), or a zonal mean by latitude and month
//! from the AFGL standard atmospheres (Anderson et al. 1986).

use crate::csv_table::tables;
use crate::spectrum::Spectrum;
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// Which ozone cross-section data set.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize, Default)]
pub enum OzoneCrossSection {
    /// Bogumil et al. (2003), 1 nm, at the scene's ozone temperature.
    #[default]
    Bogumil2003,
    /// Serdyuchenko et al. (2014) at 233 K, 10 nm bins (temperature ignored).
    Serdyuchenko233K,
}

/// Valid temperature range of the Bogumil parameterisation, K.
pub const TEMPERATURE_RANGE_K: (f64, f64) = (203.0, 293.0);

struct Bogumil {
    c0: Spectrum,
    c1: Spectrum,
    c2: Spectrum,
}

fn bogumil() -> &'static Bogumil {
    static B: OnceLock<Bogumil> = OnceLock::new();
    B.get_or_init(|| {
        let t = tables::ozone_bogumil2003();
        Bogumil {
            c0: Spectrum::from_table(t, "wavelength_nm", "C0"),
            c1: Spectrum::from_table(t, "wavelength_nm", "C1"),
            c2: Spectrum::from_table(t, "wavelength_nm", "C2"),
        }
    })
}

fn serdyuchenko() -> &'static Spectrum {
    static S: OnceLock<Spectrum> = OnceLock::new();
    S.get_or_init(|| {
        let t = tables::ozone_serdyuchenko_233k();
        // Each value is the mean over [L, L+10) nm: it belongs to the bin's centre.
        let w = t.numbers("wavelength_nm").iter().map(|w| w + 5.0).collect();
        Spectrum::new(w, t.numbers("sigma_m2")).expect("valid embedded table")
    })
}

impl OzoneCrossSection {
    /// Absorption cross-section of one ozone molecule, m² (zero outside the data's range:
    /// 300–900 nm for Bogumil, 365–835 nm for Serdyuchenko).
    pub fn cross_section_m2(self, wavelength_nm: f64, temperature_k: f64) -> f64 {
        match self {
            OzoneCrossSection::Bogumil2003 => {
                let b = bogumil();
                let dt = temperature_k - 273.15;
                let cm2 = (b.c0.sample(wavelength_nm)
                    + b.c1.sample(wavelength_nm) * dt
                    + b.c2.sample(wavelength_nm) * dt * dt)
                    * 1e-20;
                (cm2 * 1e-4).max(0.0)
            }
            OzoneCrossSection::Serdyuchenko233K => serdyuchenko().sample(wavelength_nm),
        }
    }

    pub fn cli_name(self) -> &'static str {
        match self {
            OzoneCrossSection::Bogumil2003 => "bogumil-2003",
            OzoneCrossSection::Serdyuchenko233K => "serdyuchenko-233k",
        }
    }
}

/// Mean total ozone column at Arosa for `month` (1 = January … 12), Dobson units.
pub fn monthly_column_du(month: u32) -> Option<f64> {
    let t = tables::ozone_monthly_arosa();
    let months = t.numbers("month");
    let du = t.numbers("total_ozone_DU");
    months
        .iter()
        .position(|&m| m == month as f64)
        .map(|i| du[i])
}

/// Latitudes, degrees, at which the AFGL atmospheres stand: tropical (15° N, the whole year),
/// midlatitude (45° N) and subarctic (60° N) in January ("winter") and July ("summer"),
/// as Anderson et al. (1986) define them.
const AFGL_LATITUDES_DEG: [f64; 3] = [15.0, 45.0, 60.0];

/// (summer, winter) total columns of the AFGL atmospheres at [`AFGL_LATITUDES_DEG`], DU, from
/// their own ozone profiles (ground to 120 km).
fn afgl_columns_du() -> &'static [(f64, f64); 3] {
    use crate::profiles::{AfglProfile, OzoneProfile};
    static COLUMNS: OnceLock<[(f64, f64); 3]> = OnceLock::new();
    COLUMNS.get_or_init(|| {
        let du = |p| {
            OzoneProfile::Afgl(p)
                .native_column_du(120_000.0)
                .unwrap_or(300.0)
        };
        [
            (du(AfglProfile::Tropical), du(AfglProfile::Tropical)),
            (
                du(AfglProfile::MidlatitudeSummer),
                du(AfglProfile::MidlatitudeWinter),
            ),
            (
                du(AfglProfile::SubarcticSummer),
                du(AfglProfile::SubarcticWinter),
            ),
        ]
    })
}

/// Zonal-mean total ozone column at `latitude_deg` (−90–90, north positive) in `month`
/// (1 = January … 12), DU, from the AFGL standard atmospheres (Anderson et al. 1986).
///
/// Each AFGL latitude's column runs between its winter value in January and its summer value
/// in July as a cosine of the month; between the latitudes it is linear in latitude, and held
/// at the tropical value towards the equator and at the subarctic one towards the pole. The
/// southern hemisphere takes the northern one's columns six months later (AFGL has no southern
/// atmospheres), which leaves out the Antarctic spring depletion and the south's weaker
/// seasonal cycle; and two seasons cannot place the northern maximum in spring (Arosa's is in
/// April). `None` for a month outside 1–12 or a latitude outside ±90°.
pub fn zonal_column_du(latitude_deg: f64, month: u32) -> Option<f64> {
    if !(1..=12).contains(&month) || !(-90.0..=90.0).contains(&latitude_deg) {
        return None;
    }
    let local_month = if latitude_deg < 0.0 {
        (month + 5) % 12 + 1
    } else {
        month
    };
    let winter = 0.5 * (1.0 + (2.0 * std::f64::consts::PI * (local_month - 1) as f64 / 12.0).cos());
    let at = |i: usize| {
        let (summer, winter_du) = afgl_columns_du()[i];
        summer + winter * (winter_du - summer)
    };
    let a = latitude_deg.abs();
    let l = AFGL_LATITUDES_DEG;
    Some(if a <= l[0] {
        at(0)
    } else if a >= l[2] {
        at(2)
    } else {
        let i = if a < l[1] { 0 } else { 1 };
        let t = (a - l[i]) / (l[i + 1] - l[i]);
        at(i) + t * (at(i + 1) - at(i))
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn zonal_columns_follow_latitude_and_season_in_both_hemispheres() {
        let du = |lat, m| zonal_column_du(lat, m).unwrap();
        // The AFGL atmospheres themselves at their own latitudes and months.
        let [(tropical, _), (mls, mlw), (sas, saw)] = *afgl_columns_du();
        assert!((du(15.0, 1) - tropical).abs() < 1e-9 && (du(0.0, 7) - tropical).abs() < 1e-9);
        assert!((du(45.0, 1) - mlw).abs() < 1e-9 && (du(45.0, 7) - mls).abs() < 1e-9);
        assert!((du(60.0, 1) - saw).abs() < 1e-9 && (du(80.0, 7) - sas).abs() < 1e-9);
        assert!((280.0..290.0).contains(&tropical), "{tropical}");
        assert!(mlw - mls > 30.0, "{mlw} {mls}");
        // Southern midlatitudes in January are in summer: less ozone than the north's winter,
        // exactly the north's July; Arosa's one station gave the north's January to both.
        assert!((du(-45.0, 1) - mls).abs() < 1e-9);
        assert!((du(-45.0, 7) - mlw).abs() < 1e-9);
        assert!(du(-45.0, 1) < du(45.0, 1) - 30.0);
        // Between the AFGL latitudes, between their columns; spring between winter and summer.
        let m = du(30.0, 4);
        assert!(m > du(15.0, 4).min(du(45.0, 4)) && m < du(15.0, 4).max(du(45.0, 4)));
        assert!(du(45.0, 4) < mlw && du(45.0, 4) > mls);
        assert_eq!(zonal_column_du(45.0, 0), None);
        assert_eq!(zonal_column_du(91.0, 3), None);
    }

    #[test]
    fn chappuis_band_peaks_near_600_nm() {
        let s = OzoneCrossSection::Bogumil2003;
        let peak = (500..700).max_by(|&a, &b| {
            s.cross_section_m2(a as f64, 233.0)
                .total_cmp(&s.cross_section_m2(b as f64, 233.0))
        });
        let peak = peak.unwrap();
        assert!((590..=610).contains(&peak), "peak at {peak} nm");
        // Published Chappuis maximum ≈ 5.2e-21 cm² (Bogumil et al. 2003).
        let sigma = s.cross_section_m2(602.0, 233.0);
        assert!(sigma > 4.5e-25 && sigma < 5.6e-25, "{sigma}");
    }

    #[test]
    fn bogumil_table_columns_match_the_parameterisation() {
        let t = tables::ozone_bogumil2003();
        let w = t.numbers("wavelength_nm");
        let s243 = t.numbers("sigma_243K_cm2");
        for i in (0..w.len()).step_by(37) {
            let ours = OzoneCrossSection::Bogumil2003.cross_section_m2(w[i], 243.0) * 1e4;
            assert!(
                (ours - s243[i]).abs() <= 1e-3 * s243[i].abs() + 1e-26,
                "{} nm",
                w[i]
            );
        }
    }

    #[test]
    fn the_two_data_sets_agree_in_the_chappuis_band() {
        for w in [545.0, 575.0, 605.0, 625.0] {
            let a = OzoneCrossSection::Bogumil2003.cross_section_m2(w, 233.0);
            let b = OzoneCrossSection::Serdyuchenko233K.cross_section_m2(w, 233.0);
            assert!((a / b - 1.0).abs() < 0.08, "{w} nm: {a} vs {b}");
        }
    }

    #[test]
    fn monthly_columns() {
        assert_eq!(monthly_column_du(1), Some(347.0));
        assert_eq!(monthly_column_du(10), Some(285.0));
        assert_eq!(monthly_column_du(13), None);
    }
}
