//! One measured scan held against the models: the sun placed and its azimuth estimated, the
//! aerosol found, every source's sky in the scored directions, and its errors.

use super::files::{Day, Scan};
use super::retrieve::{self, AerosolSource, RetrievalError, Retrieved};
use super::score::{self, Errors, Split};
use super::sky::{self, Site, Source, View};
use super::{aeronet, broadband, symmetry};
use atmoscope_model::methods;
use atmoscope_model::sun_position::{self, DateTime};

/// What `evaluate` computes with.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    pub site: Site,
    /// None: AERONET where the day has it, else the pyranometer.
    pub aerosol: Option<AerosolSource>,
    pub sources: Vec<Source>,
    /// Wavelengths the sources are evaluated at, nm (360–830, increasing).
    pub model_nm: Vec<f64>,
    /// Paths per direction and batch the `fit` source's trials take.
    pub fit_spp: u64,
    /// The diffuse irradiance's directions: this many squared.
    pub irradiance_strata: u32,
}

/// Wavelengths of the modelled spectra: 360–830 nm every 10 nm.
pub fn default_model_nm() -> Vec<f64> {
    (0..=47).map(|i| 360.0 + 10.0 * f64::from(i)).collect()
}

/// The id of a source in tables: a registry id or `path-tracer`.
pub fn source_id(source: &Source) -> &'static str {
    match source {
        Source::PathTracer { .. } => "path-tracer",
        Source::Model(m) => methods::info(*m).id,
    }
}

/// One source's sky over one scan.
#[derive(Debug, Clone, PartialEq)]
pub struct SourceScan {
    pub id: &'static str,
    /// Spectra (at `Settings::model_nm`) in the scored directions, in their order; empty when
    /// the model refuses the scene.
    pub radiance: Vec<Vec<f64>>,
    pub errors: Errors,
    /// cd/m², where the zenith is scored.
    pub zenith_luminance: Option<f64>,
    /// Broadband global horizontal irradiance, W·m⁻² (see [`evaluate`]).
    pub ghi_w_m2: Option<f64>,
    /// Why the model draws nothing for this scene.
    pub refused: Option<String>,
    /// The turbidity a fitted model took from the scene (its own conversion).
    pub turbidity: Option<f64>,
}

/// What a scan says and how each source did.
#[derive(Debug, Clone, PartialEq)]
pub struct ScanResult {
    pub scan: usize,
    pub sun_zenith_deg: f64,
    /// Estimated from the sky's symmetry, in the instrument's frame.
    pub sun_azimuth_deg: f64,
    /// From the date, time and place.
    pub sun_azimuth_theory_deg: f64,
    pub retrieved: Retrieved,
    /// The pyranometer's mean during the scan, W·m⁻².
    pub ghi_measured_w_m2: Option<f64>,
    /// Indices into the scan's directions of those scored (for `fit`, the held-out half).
    pub scored: Vec<usize>,
    /// For `fit`: the directions it was fitted on.
    pub fitted_on: Vec<usize>,
    pub zenith_luminance_measured: Option<f64>,
    pub sources: Vec<SourceScan>,
}

/// The sun's zenith and azimuth at the start of `scan` from the project's solar-position code.
pub fn sun_theory(day: &Day, scan: &Scan, site: &Site) -> (f64, f64) {
    let time = DateTime {
        year: day.year,
        month: day.month,
        day: day.day,
        hour: scan.time_local.hours(),
        utc_offset_h: scan.utc_offset_h(),
    };
    let a = sun_position::position(&time, site.latitude_deg, site.longitude_deg);
    (90.0 - a.elevation_deg, a.azimuth_deg.rem_euclid(360.0))
}

/// The measured luminance of each direction of a scan, cd/m² (NaN where it cannot be had).
pub fn measured_luminance(day: &Day, scan: &Scan) -> Vec<f64> {
    scan.directions
        .iter()
        .map(|d| score::xyz(&day.wavelengths_nm, &d.radiance).map_or(f64::NAN, score::luminance))
        .collect()
}

/// The sun's azimuth from the symmetry of the scan's luminance (the theoretical one where the
/// scan has no rings to tell).
pub fn sun_azimuth_from_symmetry(day: &Day, scan: &Scan, theory_deg: f64) -> f64 {
    let lum = measured_luminance(day, scan);
    let samples: Vec<symmetry::Sample> = scan
        .directions
        .iter()
        .zip(&lum)
        .filter(|(d, _)| d.sample != score::BAD_SAMPLE)
        .map(|(d, &value)| symmetry::Sample {
            azimuth_deg: d.azimuth_deg,
            elevation_deg: d.elevation_deg,
            value,
        })
        .collect();
    symmetry::sun_azimuth_deg(&samples, theory_deg).unwrap_or(theory_deg)
}

/// The view of a measured direction relative to the sun at `sun_azimuth_deg`.
pub fn view_of(scan: &Scan, index: usize, sun_azimuth_deg: f64) -> View {
    let d = &scan.directions[index];
    View {
        zenith_deg: 90.0 - d.elevation_deg,
        azimuth_from_sun_deg: d.azimuth_deg - sun_azimuth_deg,
    }
}

/// A measured spectrum at other wavelengths, linear between its own.
pub fn resample(day: &Day, radiance: &[f64], nm: &[f64]) -> Vec<f64> {
    let s = score::spectrum(&day.wavelengths_nm, radiance);
    nm.iter()
        .map(|&w| s.as_ref().map_or(f64::NAN, |s| s.sample(w)))
        .collect()
}

/// The views of the directions `fit_half` of `scan` and their measured spectra at
/// [`retrieve::FIT_NM`]: what the fit compares.
pub fn fit_spectra(
    day: &Day,
    scan: &Scan,
    fit_half: &[usize],
    sun_azimuth_deg: f64,
) -> (Vec<View>, Vec<Vec<f64>>) {
    let views = fit_half
        .iter()
        .map(|&i| view_of(scan, i, sun_azimuth_deg))
        .collect();
    let measured = fit_half
        .iter()
        .map(|&i| resample(day, &scan.directions[i].radiance, &retrieve::FIT_NM))
        .collect();
    (views, measured)
}

/// The scan's aerosol from `source`.
pub fn retrieve(
    day: &Day,
    scan_index: usize,
    source: AerosolSource,
    settings: &Settings,
    fit_half: &[usize],
    sun_azimuth_deg: f64,
) -> Result<Retrieved, RetrievalError> {
    let scan = &day.scans[scan_index];
    match source {
        AerosolSource::Aeronet => retrieve::from_aeronet(day, scan),
        AerosolSource::Pyranometer => retrieve::from_pyranometer(day, scan_index, &settings.site),
        AerosolSource::Fit => {
            let shape = retrieve::shape(day, scan);
            let (views, measured) = fit_spectra(day, scan, fit_half, sun_azimuth_deg);
            let scene_at = |aod550, ssa| {
                sky::scene(
                    day,
                    scan,
                    &settings.site,
                    &sky::Aerosol {
                        aod550,
                        ssa,
                        ..shape
                    },
                )
            };
            let start = aeronet::at(&day.aeronet, scan.time_utc).map_or(0.1, |a| a.aod550);
            let (aod550, ssa) = retrieve::fit_aerosol(
                scene_at,
                &views,
                &measured,
                settings.fit_spp,
                (start, shape.ssa),
            );
            Ok(Retrieved {
                source,
                aerosol: sky::Aerosol {
                    aod550,
                    ssa,
                    ..shape
                },
                note: format!(
                    "optical depth and albedo fitted by the path tracer on {} directions",
                    fit_half.len()
                ),
            })
        }
    }
}

/// The aerosol source `evaluate` uses for `day` when none is asked for.
pub fn default_source(day: &Day) -> AerosolSource {
    if day.aeronet.is_empty() {
        AerosolSource::Pyranometer
    } else {
        AerosolSource::Aeronet
    }
}

/// Holds scan `scan_index` of `day` against every source of `settings`.
///
/// The global horizontal irradiance of each source is its direct and diffuse irradiance over
/// 360–830 nm times the ratio of the broadband model's global irradiance (Bird & Hulstrom
/// 1981, at the scan's aerosol) to the path tracer's over that band: the atmosphere's physics
/// stops at 830 nm, the pyranometer's at 2800 nm. The path tracer's figure is therefore the
/// broadband model's; each model's differs from it as its band's sky differs from the path
/// tracer's.
pub fn evaluate(
    day: &Day,
    scan_index: usize,
    settings: &Settings,
) -> Result<ScanResult, RetrievalError> {
    let scan = &day.scans[scan_index];
    let (sun_zenith_deg, sun_azimuth_theory_deg) = sun_theory(day, scan, &settings.site);
    let sun_azimuth_deg = sun_azimuth_from_symmetry(day, scan, sun_azimuth_theory_deg);
    let usable = score::scored_directions(scan, sun_zenith_deg, sun_azimuth_deg);
    let source = settings.aerosol.unwrap_or_else(|| default_source(day));
    let (scored, fitted_on) = match source {
        AerosolSource::Fit => {
            let split = Split::alternate(&usable);
            (split.score, split.fit)
        }
        _ => (usable, Vec::new()),
    };
    let retrieved = retrieve(
        day,
        scan_index,
        source,
        settings,
        &fitted_on,
        sun_azimuth_deg,
    )?;
    let scene = sky::scene(day, scan, &settings.site, &retrieved.aerosol);
    let views: Vec<View> = scored
        .iter()
        .map(|&i| view_of(scan, i, sun_azimuth_deg))
        .collect();
    let measured: Vec<&[f64]> = scored
        .iter()
        .map(|&i| scan.directions[i].radiance.as_slice())
        .collect();
    let zenith = scored
        .iter()
        .position(|&i| scan.directions[i].elevation_deg > 89.9);
    let zenith_luminance_measured = zenith
        .and_then(|z| score::xyz(&day.wavelengths_nm, measured[z]))
        .map(score::luminance);

    // The broadband scale of the irradiance: Bird & Hulstrom over the path tracer's band.
    let truth_band = sky::Sky::new(
        &scene,
        Source::PathTracer { spp: 16, seed: 3 },
        &settings.model_nm,
    )
    .ok()
    .map(|s| s.horizontal_irradiance(settings.irradiance_strata));
    let broadband = broadband::global(&retrieve::broadband_inputs(
        &scene,
        &settings.site,
        &retrieved.aerosol,
    ));
    let to_broadband = match (truth_band, broadband) {
        (Some(b), Some(g)) if b.global() > 0.0 => Some(g / b.global()),
        _ => None,
    };

    let sources = settings
        .sources
        .iter()
        .map(|source| {
            let id = source_id(source);
            match sky::Sky::new(&scene, *source, &settings.model_nm) {
                Err(why) => SourceScan {
                    id,
                    radiance: Vec::new(),
                    errors: Errors::default(),
                    zenith_luminance: None,
                    ghi_w_m2: None,
                    refused: Some(why.to_string()),
                    turbidity: None,
                },
                Ok(sky) => {
                    let radiance = sky.radiance(&views);
                    let modelled: Vec<&[f64]> = radiance.iter().map(Vec::as_slice).collect();
                    let errors = score::compare(
                        &day.wavelengths_nm,
                        &measured,
                        &settings.model_nm,
                        &modelled,
                    );
                    let zenith_luminance = zenith
                        .and_then(|z| score::xyz(&settings.model_nm, &radiance[z]))
                        .map(score::luminance);
                    let band = match source {
                        Source::PathTracer { .. } => truth_band,
                        Source::Model(_) => {
                            Some(sky.horizontal_irradiance(settings.irradiance_strata))
                        }
                    };
                    let ghi_w_m2 = band.zip(to_broadband).map(|(b, k)| b.global() * k);
                    SourceScan {
                        id,
                        radiance,
                        errors,
                        zenith_luminance,
                        ghi_w_m2,
                        refused: None,
                        turbidity: sky.turbidity(),
                    }
                }
            }
        })
        .collect();
    Ok(ScanResult {
        scan: scan_index,
        sun_zenith_deg,
        sun_azimuth_deg,
        sun_azimuth_theory_deg,
        retrieved,
        ghi_measured_w_m2: day.ghi_during(scan_index),
        scored,
        fitted_on,
        zenith_luminance_measured,
        sources,
    })
}
