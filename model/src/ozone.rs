//! Ozone absorption: cross-sections and the monthly total column.
//!
//! Bogumil et al. (2003) give σ(λ, T) = (C₀ + C₁·ΔT + C₂·ΔT²)·10⁻²⁰ cm², ΔT = T − 273.15 K,
//! valid for about 203–293 K (the ozone layer is near 220–240 K). Serdyuchenko/Gorshelev et al.
//! (2014) at 233 K in 10 nm bins is the set Bruneton (2017) uses. Monthly columns are the Arosa
//! means of Dütsch (1973) used by Guimera et al. (2018).

use crate::spectrum::Spectrum;
use crate::table::tables;
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

#[cfg(test)]
mod tests {
    use super::*;

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
