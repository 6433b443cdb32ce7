//! Rayleigh scattering by air molecules.
//!
//! Cross-section from the standard-air volume scattering coefficients tabulated by Bucholtz
//! (1995), σ = β_s/N_s, interpolated log–log (exact for a power law, close to λ⁻⁴ here); the
//! wavelength-dependent depolarisation ratio from the King factors of Bates (1984) as combined by
//! Bodhaine et al. (1999), which feeds the phase function's anisotropy correction.

use crate::constants::STANDARD_AIR_NUMBER_DENSITY_M3;
use crate::csv_table::tables;
use crate::spectrum::Spectrum;
use std::sync::OnceLock;

fn beta_standard_per_km() -> &'static Spectrum {
    static S: OnceLock<Spectrum> = OnceLock::new();
    S.get_or_init(|| {
        Spectrum::from_table(
            tables::rayleigh_bucholtz1995(),
            "wavelength_nm",
            "beta_s_km",
        )
    })
}

fn depolarisation_table() -> &'static Spectrum {
    static S: OnceLock<Spectrum> = OnceLock::new();
    S.get_or_init(|| {
        Spectrum::from_table(
            tables::rayleigh_air_derived(),
            "wavelength_nm",
            "depolarization_ratio",
        )
    })
}

/// Rayleigh scattering cross-section of one air molecule at `wavelength_nm` (200–4000 nm), m².
pub fn cross_section_m2(wavelength_nm: f64) -> f64 {
    beta_standard_per_km().sample_log_log(wavelength_nm) * 1e-3 / STANDARD_AIR_NUMBER_DENSITY_M3
}

/// Depolarisation ratio ρ of air (about 0.03 in the visible); clamped to the table's ends
/// (360–830 nm) outside it.
pub fn depolarisation_ratio(wavelength_nm: f64) -> f64 {
    let t = depolarisation_table();
    let (lo, hi) = t.range_nm();
    t.sample(wavelength_nm.clamp(lo, hi))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bucholtz_cross_section_agrees_with_the_derived_bodhaine_table() {
        let derived =
            Spectrum::from_table(tables::rayleigh_air_derived(), "wavelength_nm", "sigma_cm2");
        for w in [400.0, 455.0, 550.0, 633.0, 700.0, 800.0] {
            let ratio = cross_section_m2(w) / (derived.sample(w) * 1e-4);
            assert!((ratio - 1.0).abs() < 3e-3, "{w} nm: ratio {ratio}");
        }
    }

    #[test]
    fn depolarisation_is_about_three_percent() {
        for w in [360.0, 550.0, 830.0, 1000.0] {
            let r = depolarisation_ratio(w);
            assert!(r > 0.026 && r < 0.032, "{w}: {r}");
        }
    }
}
