//! The aerosol of a measured scan, three ways:
//! - `aeronet`: the sun photometer's optical depth and Ångström exponent, and the asymmetry of
//!   its retrieved phase function, interpolated to the scan's time ([`super::aeronet`]);
//! - `pyranometer`: the optical depth at which the broadband model of Bird & Hulstrom (1981)
//!   ([`super::broadband`]) gives the pyranometer's global irradiance during the scan: no
//!   radiance is used, so the sky that follows is a prediction;
//! - `fit`: the optical depth and single-scattering albedo at which the path tracer's sky is
//!   closest to the scan's radiance (least squares in ln L) on one half of its directions
//!   ([`super::score::Split`]); the sky is then scored on the other half only.

use super::aeronet;
use super::broadband;
use super::files::{Day, Scan};
use super::sky::{self, Aerosol, Site, Source, View};
use atmoscope_model::Scene;
use std::fmt;

/// Where a scan's aerosol comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AerosolSource {
    Aeronet,
    Pyranometer,
    Fit,
}

impl AerosolSource {
    pub const ALL: [AerosolSource; 3] = [
        AerosolSource::Aeronet,
        AerosolSource::Pyranometer,
        AerosolSource::Fit,
    ];

    /// The command line's name.
    pub fn name(self) -> &'static str {
        match self {
            AerosolSource::Aeronet => "aeronet",
            AerosolSource::Pyranometer => "pyranometer",
            AerosolSource::Fit => "fit",
        }
    }

    pub fn from_name(s: &str) -> Option<AerosolSource> {
        AerosolSource::ALL.into_iter().find(|a| a.name() == s)
    }
}

impl fmt::Display for AerosolSource {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Why a scan's aerosol cannot be had from a source.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RetrievalError {
    #[error("the day {0} has no AERONET record (no .pfn file for it in the folder)")]
    NoAeronet(String),
    #[error("scan {0} has no pyranometer reading")]
    NoPyranometer(String),
    #[error("the sun is too low for the broadband model at scan {0}")]
    SunTooLow(String),
}

/// The aerosol found for a scan and how.
#[derive(Debug, Clone, PartialEq)]
pub struct Retrieved {
    pub source: AerosolSource,
    pub aerosol: Aerosol,
    /// One line on how it was found (the record's distance in time, the irradiance matched).
    pub note: String,
}

/// The Ångström exponent and asymmetry the AERONET file gives at the scan's time (the
/// defaults without one): what every source takes for the aerosol's spectral shape and
/// phase, so that the sources differ in the optical depth alone.
pub fn shape(day: &Day, scan: &Scan) -> Aerosol {
    let mut a = Aerosol::default();
    if let Some(at) = aeronet::at(&day.aeronet, scan.time_utc) {
        a.angstrom = at.angstrom;
        if let Some(g) = at.asymmetry_g550 {
            a.asymmetry_g = g;
        }
    }
    a
}

/// The aerosol from the AERONET records of the scan's day.
pub fn from_aeronet(day: &Day, scan: &Scan) -> Result<Retrieved, RetrievalError> {
    let at = aeronet::at(&day.aeronet, scan.time_utc)
        .ok_or_else(|| RetrievalError::NoAeronet(day.date.clone()))?;
    Ok(Retrieved {
        source: AerosolSource::Aeronet,
        aerosol: Aerosol {
            aod550: at.aod550,
            ..shape(day, scan)
        },
        note: format!(
            "AERONET, {:.1} h from the nearest record",
            at.hours_to_record
        ),
    })
}

/// The inputs of the broadband model for a scene at a site.
pub fn broadband_inputs(scene: &Scene, site: &Site, aerosol: &Aerosol) -> broadband::Inputs {
    let a = scene.sun.angles();
    let top_m = scene.atmosphere.top_km * 1000.0;
    let tau = |w: f64| aerosol.aod550 * (w / 550.0).powf(-aerosol.angstrom);
    broadband::Inputs {
        sun_zenith_deg: 90.0 - a.elevation_deg,
        pressure_ratio: site.pressure_ratio(),
        ozone_cm: scene.atmosphere.ozone.column_du(top_m) / 1000.0,
        water_cm: broadband::DEFAULT_WATER_CM,
        aod380: tau(380.0),
        aod500: tau(500.0),
        albedo: broadband::GRASS_ALBEDO,
        sunlight_scale: scene.sun.sunlight_scale(),
    }
}

/// The aerosol whose broadband global irradiance is the pyranometer's mean during the scan.
pub fn from_pyranometer(
    day: &Day,
    scan_index: usize,
    site: &Site,
) -> Result<Retrieved, RetrievalError> {
    let scan = &day.scans[scan_index];
    let label = format!("{} {}", day.date, scan.time_local);
    let measured = day
        .ghi_during(scan_index)
        .ok_or_else(|| RetrievalError::NoPyranometer(label.clone()))?;
    let shape = shape(day, scan);
    let scene = sky::scene(day, scan, site, &shape);
    let inputs = broadband_inputs(&scene, site, &shape);
    let aod550 = broadband::aod550_from_global(measured, &inputs, shape.angstrom)
        .ok_or(RetrievalError::SunTooLow(label))?;
    let clean = broadband::global(&broadband::Inputs {
        aod380: 0.0,
        aod500: 0.0,
        ..inputs
    });
    let note = match clean {
        Some(g) if aod550 == 0.0 => format!(
            "none: the pyranometer's {measured:.1} W/m² is {:.1} % above an aerosol-free sky's (Bird & Hulstrom 1981)",
            100.0 * (measured / g - 1.0)
        ),
        _ => format!("matches the pyranometer's {measured:.1} W/m² (Bird & Hulstrom 1981)"),
    };
    Ok(Retrieved {
        source: AerosolSource::Pyranometer,
        aerosol: Aerosol { aod550, ..shape },
        note,
    })
}

/// Wavelengths the fit compares, nm: across the scored range, two batches of four.
pub const FIT_NM: [f64; 8] = [380.0, 420.0, 460.0, 500.0, 550.0, 600.0, 650.0, 700.0];
/// Range of optical depths at 550 nm the fit searches.
pub const FIT_AOD_RANGE: (f64, f64) = (0.0, 1.5);

/// Range of single-scattering albedos the fit searches.
pub const FIT_SSA_RANGE: (f64, f64) = (0.6, 1.0);

/// Optical depths at 550 nm and albedos of the coarse grid the fit's simplex starts from.
const FIT_START_AOD: [f64; 7] = [0.03, 0.08, 0.15, 0.25, 0.4, 0.65, 1.0];
const FIT_START_SSA: [f64; 3] = [0.8, 0.9, 0.97];

/// What [`fit_aerosol`] minimises: the mean squared ln ratio of the path tracer's sky over
/// `scene` (`spp` paths per direction and batch, the fit's one seed) to `measured` (spectra at
/// [`FIT_NM`], one per view), over the samples where both are positive; infinite where there
/// are none or the path tracer refuses the scene.
pub fn fit_misfit(scene: &Scene, views: &[View], measured: &[Vec<f64>], spp: u64) -> f64 {
    let Ok(model) = sky::radiance(scene, Source::PathTracer { spp, seed: 7 }, views, &FIT_NM)
    else {
        return f64::INFINITY;
    };
    let (mut sum, mut n) = (0.0, 0usize);
    for (m, l) in measured.iter().zip(&model) {
        for (m, l) in m.iter().zip(l) {
            if *m > 0.0 && *l > 0.0 {
                sum += (l / m).ln().powi(2);
                n += 1;
            }
        }
    }
    if n == 0 {
        f64::INFINITY
    } else {
        sum / n as f64
    }
}

/// The optical depth at 550 nm and the single-scattering albedo at which the path tracer's sky
/// over `scene_at(aod, ssa)` fits `measured` best by [`fit_misfit`] (one seed for every trial,
/// so the misfit is smooth), by Nelder–Mead within [`FIT_AOD_RANGE`] and [`FIT_SSA_RANGE`]. It
/// reads nothing but the views and spectra it is given: the caller hands it one half of a split.
pub fn fit_aerosol(
    scene_at: impl Fn(f64, f64) -> Scene,
    views: &[View],
    measured: &[Vec<f64>],
    spp: u64,
    start: (f64, f64),
) -> (f64, f64) {
    let clamp = |x: &[f64]| {
        (
            x[0].clamp(FIT_AOD_RANGE.0, FIT_AOD_RANGE.1),
            x[1].clamp(FIT_SSA_RANGE.0, FIT_SSA_RANGE.1),
        )
    };
    let misfit = |x: &[f64]| -> f64 {
        let (aod, ssa) = clamp(x);
        // Outside the ranges the misfit grows with the distance, so the simplex comes back.
        let outside = (x[0] - aod).abs() + (x[1] - ssa).abs();
        fit_misfit(&scene_at(aod, ssa), views, measured, spp) + outside
    };
    // The valley where depth trades against albedo is long and narrow, and one seed for every
    // trial still leaves the misfit rough on the scale of the path tracer's noise, so a simplex
    // started anywhere stops in the nearest dip. It starts instead at the best of `start` and a
    // coarse grid over both ranges.
    let grid = FIT_START_AOD
        .iter()
        .flat_map(|&aod| FIT_START_SSA.iter().map(move |&ssa| [aod, ssa]));
    let start = std::iter::once([start.0, start.1])
        .chain(grid)
        .map(|x| {
            let (aod, ssa) = clamp(&x);
            (misfit(&[aod, ssa]), [aod, ssa])
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map_or([start.0, start.1], |(_, x)| x);
    let (best, _) = crate::optimize::nelder_mead(&misfit, &start, &[0.05, -0.05], 1e-4, 80);
    clamp(&best)
}
