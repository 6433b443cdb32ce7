//! `atmoscope bench measured`: every model and the path tracer against measured spectral sky
//! radiance (Kider et al. 2014 and any folder in its format), scored as Bruneton (2017) did:
//! over 360–720 nm and the directions more than 10° from the sun, sample 0 left out. The
//! physics is `atmoscope_eval::measured`; this module reads the arguments, runs the scans and
//! writes the table, the JSON, the CSV files and the charts (`measured_charts`).

use super::measured_charts;
use anyhow::{Context, bail};
use atmoscope_eval::measured::files::{self, Day};
use atmoscope_eval::measured::retrieve::AerosolSource;
use atmoscope_eval::measured::run::{self, ScanResult, Settings};
use atmoscope_eval::measured::score::{self, Errors, SCORED_NM, SUN_EXCLUSION_DEG};
use atmoscope_eval::measured::sky::{self, Site, Source};
use atmoscope_model::methods;
use clap::Args;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Args, Debug)]
pub struct MeasuredBench {
    /// A folder of measured days: radiance_<date>.csv and scans_<date>.csv, optionally
    /// pyranometer_<date>.csv and an AERONET .pfn file (default: the shipped day, Kider et
    /// al. 2014 over Cornell).
    #[arg(long, value_name = "DIR")]
    pub data: Option<PathBuf>,
    /// Models, comma-separated: registry ids and `path-tracer`, or `all` (every real-time
    /// model and the path tracer).
    #[arg(long, value_name = "LIST", default_value = "all", value_parser = parse_sources)]
    pub models: SourceList,
    /// Where the aerosol comes from: aeronet (the .pfn file at the scan's time), pyranometer
    /// (retrieved from the measured global irradiance alone) or fit (fitted on half the
    /// directions, scored on the other half). Default: aeronet where the day has a .pfn file,
    /// else pyranometer.
    #[arg(long, value_parser = parse_aerosol)]
    pub aerosol: Option<AerosolSource>,
    /// Where the summary (measured.md), the JSON, a CSV per scan and the charts go.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Print the results as one JSON object instead of the table.
    #[arg(long)]
    pub json: bool,
    /// The site: latitude (°N), longitude (°E) and altitude (m). Default: Kider's roof at
    /// Cornell, 42.443449,-76.481962,250.
    #[arg(long, value_name = "LAT,LON,ALT_M", value_parser = parse_site, allow_hyphen_values = true)]
    pub site: Option<Site>,
    /// Only these scans, comma-separated local start times (e.g. 09:30,12:00).
    #[arg(long, value_name = "TIMES", value_delimiter = ',')]
    pub scans: Vec<String>,
    /// Path-tracer paths per direction and batch of four wavelengths.
    #[arg(long, default_value_t = 512, value_parser = clap::value_parser!(u64).range(16..))]
    pub spp: u64,
}

#[derive(Debug, Clone)]
pub struct SourceList(pub Vec<Source>);

fn parse_sources(list: &str) -> Result<SourceList, String> {
    let tracer = Source::PathTracer { spp: 0, seed: 1 };
    if list == "all" {
        let mut v: Vec<Source> = methods::realtime()
            .map(|m| Source::Model(m.method))
            .collect();
        v.push(tracer);
        return Ok(SourceList(v));
    }
    list.split(',')
        .map(str::trim)
        .map(|id| match id {
            "path-tracer" => Ok(tracer),
            id => crate::args::parse_method(id).map(Source::Model),
        })
        .collect::<Result<_, _>>()
        .map(SourceList)
}

fn parse_aerosol(s: &str) -> Result<AerosolSource, String> {
    AerosolSource::from_name(s)
        .ok_or_else(|| format!("no aerosol source `{s}` (aeronet, pyranometer, fit)"))
}

fn parse_site(s: &str) -> Result<Site, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| {
            x.trim()
                .parse::<f64>()
                .map_err(|_| format!("`{x}` is not a number"))
        })
        .collect::<Result<_, _>>()?;
    let [latitude_deg, longitude_deg, altitude_m] = v[..] else {
        return Err("expected LAT,LON,ALT_M".into());
    };
    if !(-90.0..=90.0).contains(&latitude_deg) {
        return Err(format!("latitude {latitude_deg}° is outside −90 to 90°"));
    }
    if !(-180.0..=180.0).contains(&longitude_deg) {
        return Err(format!(
            "longitude {longitude_deg}° is outside −180 to 180°"
        ));
    }
    if !(0.0..=5000.0).contains(&altitude_m) {
        return Err(format!("altitude {altitude_m} m is outside 0 to 5000 m"));
    }
    Ok(Site {
        latitude_deg,
        longitude_deg,
        altitude_m,
    })
}

/// One scan as the JSON reports it.
#[derive(Serialize, Debug, Clone)]
pub struct ScanRow {
    pub date: String,
    pub time_local: String,
    pub sun_zenith_deg: f64,
    pub sun_azimuth_deg: f64,
    pub sun_azimuth_theory_deg: f64,
    pub aerosol: AerosolRow,
    pub ghi_measured_w_m2: Option<f64>,
    pub zenith_luminance_measured_cd_m2: Option<f64>,
    /// Directions scored (for `fit`, the held-out half).
    pub directions_scored: usize,
}

#[derive(Serialize, Debug, Clone)]
pub struct AerosolRow {
    pub source: String,
    pub aod550: f64,
    pub angstrom: f64,
    pub asymmetry_g: f64,
    pub single_scattering_albedo: f64,
    pub note: String,
}

/// One model over every scan.
#[derive(Serialize, Debug, Clone)]
pub struct ModelRow {
    pub id: String,
    pub radiance_median_abs_rel_err: f64,
    pub radiance_p95_abs_rel_err: f64,
    pub luminance_median_abs_rel_err: f64,
    /// Median distance in CIE 1976 u′v′.
    pub chromaticity_median_delta_uv: f64,
    pub zenith_luminance_median_abs_rel_err: f64,
    pub ghi_median_abs_rel_err: f64,
    /// Spectral radiance samples (direction × wavelength) scored.
    pub samples: usize,
    /// Scans the model refused (outside its domain).
    pub refused_scans: usize,
    /// The median turbidity a fitted model took from the scans' scenes by its own conversion
    /// (Preetham, Hosek–Wilkie, the CIE sky); absent for the others.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub turbidity_median: Option<f64>,
}

#[derive(Serialize, Debug)]
pub struct Report {
    pub scans: Vec<ScanRow>,
    pub models: Vec<ModelRow>,
    /// Scans left out, and why.
    pub skipped: Vec<SkippedScan>,
}

#[derive(Serialize, Debug, Clone)]
pub struct SkippedScan {
    pub scan: String,
    pub reason: String,
}

/// The model rows of a set of scan results, in the order of `ids`.
pub fn model_rows(ids: &[&str], results: &[ScanResult]) -> Vec<ModelRow> {
    ids.iter()
        .map(|&id| {
            let mut errors = Errors::default();
            let (mut zenith, mut ghi, mut refused, mut turbidity) =
                (Vec::new(), Vec::new(), 0, Vec::new());
            for r in results {
                let Some(s) = r.sources.iter().find(|s| s.id == id) else {
                    continue;
                };
                if s.refused.is_some() {
                    refused += 1;
                    continue;
                }
                errors.extend(&s.errors);
                turbidity.extend(s.turbidity);
                if let (Some(m), Some(l)) = (r.zenith_luminance_measured, s.zenith_luminance) {
                    zenith.push((l / m - 1.0).abs());
                }
                if let (Some(m), Some(g)) = (r.ghi_measured_w_m2, s.ghi_w_m2) {
                    ghi.push((g / m - 1.0).abs());
                }
            }
            ModelRow {
                id: id.to_owned(),
                radiance_median_abs_rel_err: score::quantile(&errors.radiance, 0.5),
                radiance_p95_abs_rel_err: score::quantile(&errors.radiance, 0.95),
                luminance_median_abs_rel_err: score::quantile(&errors.luminance, 0.5),
                chromaticity_median_delta_uv: score::quantile(&errors.chromaticity, 0.5),
                zenith_luminance_median_abs_rel_err: score::quantile(&zenith, 0.5),
                ghi_median_abs_rel_err: score::quantile(&ghi, 0.5),
                samples: errors.radiance.len(),
                refused_scans: refused,
                turbidity_median: (!turbidity.is_empty()).then(|| score::quantile(&turbidity, 0.5)),
            }
        })
        .collect()
}

pub fn scan_row(day: &Day, r: &ScanResult) -> ScanRow {
    let a = &r.retrieved.aerosol;
    ScanRow {
        date: day.date.clone(),
        time_local: day.scans[r.scan].time_local.to_string(),
        sun_zenith_deg: r.sun_zenith_deg,
        sun_azimuth_deg: r.sun_azimuth_deg,
        sun_azimuth_theory_deg: r.sun_azimuth_theory_deg,
        aerosol: AerosolRow {
            source: r.retrieved.source.name().into(),
            aod550: a.aod550,
            angstrom: a.angstrom,
            asymmetry_g: a.asymmetry_g,
            single_scattering_albedo: a.ssa,
            note: r.retrieved.note.clone(),
        },
        ghi_measured_w_m2: r.ghi_measured_w_m2,
        zenith_luminance_measured_cd_m2: r.zenith_luminance_measured,
        directions_scored: r.scored.len(),
    }
}

pub fn run(args: &MeasuredBench) -> anyhow::Result<ExitCode> {
    let folder = args
        .data
        .clone()
        .unwrap_or_else(atmoscope_eval::measured::shipped_folder);
    let days = files::read_folder(&folder)?;
    if let Some(out) = &args.out {
        crate::files::check_writable(out)?;
    }
    let sources: Vec<Source> = args
        .models
        .0
        .iter()
        .map(|s| match s {
            Source::PathTracer { seed, .. } => Source::PathTracer {
                spp: args.spp,
                seed: *seed,
            },
            m => *m,
        })
        .collect();
    let settings = Settings {
        site: args.site.unwrap_or(Site::CORNELL),
        aerosol: args.aerosol,
        sources,
        model_nm: run::default_model_nm(),
        fit_spp: 96,
        irradiance_strata: 12,
    };
    let mut chosen: Vec<(usize, usize)> = Vec::new();
    for (d, day) in days.iter().enumerate() {
        for (s, scan) in day.scans.iter().enumerate() {
            if args.scans.is_empty() || args.scans.iter().any(|t| *t == scan.time_local.to_string())
            {
                chosen.push((d, s));
            }
        }
    }
    if chosen.is_empty() {
        bail!(
            "--scans: no scan of {} starts at {}",
            folder.display(),
            args.scans.join(", ")
        );
    }
    let mut results: Vec<(usize, ScanResult)> = Vec::new();
    let mut skipped = Vec::new();
    for (k, &(d, s)) in chosen.iter().enumerate() {
        let day = &days[d];
        let label = format!("{} {}", day.date, day.scans[s].time_local);
        eprintln!("bench measured: {label} ({}/{})", k + 1, chosen.len());
        match run::evaluate(day, s, &settings) {
            Ok(r) => results.push((d, r)),
            // A scan the chosen source says nothing of (no pyranometer reading, no AERONET
            // record) is left out and named; the others are still scored.
            Err(e) => {
                eprintln!("bench measured: {label} left out: {e}");
                skipped.push(SkippedScan {
                    scan: label,
                    reason: e.to_string(),
                });
            }
        }
    }
    if results.is_empty() {
        bail!(
            "no scan could be scored: {}",
            skipped
                .iter()
                .map(|s| format!("{}: {}", s.scan, s.reason))
                .collect::<Vec<_>>()
                .join("; ")
        );
    }
    let ids: Vec<&str> = settings.sources.iter().map(run::source_id).collect();
    let all: Vec<ScanResult> = results.iter().map(|(_, r)| r.clone()).collect();
    let report = Report {
        scans: results
            .iter()
            .map(|(d, r)| scan_row(&days[*d], r))
            .collect(),
        models: model_rows(&ids, &all),
        skipped,
    };
    let summary = summary(&report, &settings, &folder);
    if let Some(out) = &args.out {
        write_outputs(out, &days, &results, &report, &summary, &settings)?;
    }
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print!("{summary}");
    }
    Ok(ExitCode::SUCCESS)
}

fn pct(x: f64) -> String {
    if x.is_finite() {
        format!("{:.1} %", 100.0 * x)
    } else {
        "–".into()
    }
}

/// The Markdown summary: the models ranked by their median radiance error, then the scans.
pub fn summary(report: &Report, settings: &Settings, folder: &std::path::Path) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "# Models against measured skies\n");
    let _ = writeln!(
        s,
        "{} scans from `{}`. Scored over {}–{} nm and the directions more than {}° from the sun, \
         sample 0 left out; errors are |model/measured − 1| pooled over every scan.\n",
        report.scans.len(),
        folder.display(),
        SCORED_NM.0,
        SCORED_NM.1,
        SUN_EXCLUSION_DEG
    );
    let mut models = report.models.clone();
    models.sort_by(|a, b| {
        a.radiance_median_abs_rel_err
            .total_cmp(&b.radiance_median_abs_rel_err)
    });
    let _ = writeln!(
        s,
        "| model | radiance median | radiance p95 | luminance median | Δu′v′ median | zenith luminance | GHI | samples |"
    );
    let _ = writeln!(s, "| --- | --- | --- | --- | --- | --- | --- | --- |");
    for m in &models {
        let refused = if m.refused_scans > 0 {
            format!(" (refused {} scans)", m.refused_scans)
        } else {
            String::new()
        };
        let refused = match m.turbidity_median {
            Some(t) => format!("{refused} (turbidity {t:.2})"),
            None => refused,
        };
        let _ = writeln!(
            s,
            "| {}{refused} | {} | {} | {} | {:.4} | {} | {} | {} |",
            m.id,
            pct(m.radiance_median_abs_rel_err),
            pct(m.radiance_p95_abs_rel_err),
            pct(m.luminance_median_abs_rel_err),
            m.chromaticity_median_delta_uv,
            pct(m.zenith_luminance_median_abs_rel_err),
            pct(m.ghi_median_abs_rel_err),
            m.samples
        );
    }
    let _ = writeln!(s, "\n## Scans\n");
    let _ = writeln!(
        s,
        "| date | local time | sun zenith | sun azimuth (symmetry / theory) | aerosol | AOD 550 | Ångström | SSA | GHI measured | zenith luminance |"
    );
    let _ = writeln!(
        s,
        "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    );
    for r in &report.scans {
        let _ = writeln!(
            s,
            "| {} | {} | {:.2}° | {:.2}° / {:.2}° | {} | {:.3} | {:.2} | {:.2} | {} | {} |",
            r.date,
            r.time_local,
            r.sun_zenith_deg,
            r.sun_azimuth_deg,
            r.sun_azimuth_theory_deg,
            r.aerosol.source,
            r.aerosol.aod550,
            r.aerosol.angstrom,
            r.aerosol.single_scattering_albedo,
            r.ghi_measured_w_m2
                .map_or("–".into(), |g| format!("{g:.1} W/m²")),
            r.zenith_luminance_measured_cd_m2
                .map_or("–".into(), |l| format!("{l:.0} cd/m²")),
        );
    }
    for k in &report.skipped {
        let _ = writeln!(s, "\nLeft out: {} ({}).", k.scan, k.reason);
    }
    let _ = writeln!(
        s,
        "\nThe scene of each scan: the sun by date, time and place (zenith angle; azimuth from the \
         sky's symmetry), the site's air column (pressure ratio {:.4}), zonal-mean ozone of the \
         latitude and month, a grass ground, a Custom aerosol (Henyey–Greenstein, SSA {} unless \
         fitted, scale height {} km). GHI: each sky's 360–830 nm irradiance carried to broadband by Bird & \
         Hulstrom (1981) over the path tracer's band.",
        settings.site.pressure_ratio(),
        sky::DEFAULT_SSA,
        sky::AEROSOL_SCALE_HEIGHT_KM,
    );
    s
}

fn write_outputs(
    out: &std::path::Path,
    days: &[Day],
    results: &[(usize, ScanResult)],
    report: &Report,
    summary: &str,
    settings: &Settings,
) -> anyhow::Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    crate::files::write_atomic(&out.join("measured.md"), summary.as_bytes())?;
    crate::files::write_atomic(
        &out.join("measured.json"),
        serde_json::to_string_pretty(report)?.as_bytes(),
    )?;
    for (d, r) in results {
        let day = &days[*d];
        let scan = &day.scans[r.scan];
        let lum = run::measured_luminance(day, scan);
        let mut csv = String::from(
            "model,sample,azimuth_deg,elevation_deg,luminance_measured_cd_m2,luminance_model_cd_m2,luminance_rel_err,radiance_median_abs_rel_err\n",
        );
        for s in r.sources.iter().filter(|s| s.refused.is_none()) {
            for (k, &i) in r.scored.iter().enumerate() {
                let dir = &scan.directions[i];
                let l = score::xyz(&settings.model_nm, &s.radiance[k])
                    .map_or(f64::NAN, score::luminance);
                let e = score::compare(
                    &day.wavelengths_nm,
                    &[&dir.radiance],
                    &settings.model_nm,
                    &[&s.radiance[k]],
                );
                let _ = writeln!(
                    csv,
                    "{},{},{},{},{:.6e},{:.6e},{:.5},{:.5}",
                    s.id,
                    dir.sample,
                    dir.azimuth_deg,
                    dir.elevation_deg,
                    lum[i],
                    l,
                    l / lum[i] - 1.0,
                    score::quantile(&e.radiance, 0.5)
                );
            }
        }
        let name = format!(
            "scan_{}_{}.csv",
            day.date,
            scan.time_local.to_string().replace(':', "")
        );
        crate::files::write_atomic(&out.join(name), csv.as_bytes())?;
    }
    measured_charts::write(out, days, results, settings)
}
