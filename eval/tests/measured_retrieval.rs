//! Each aerosol retrieval finds again the optical depth of a synthetic sky, and the
//! cross-validated fit never scores a direction it was fitted on.

use atmoscope_eval::measured::files::{self, Day, GhiSample};
use atmoscope_eval::measured::retrieve::{self, AerosolSource};
use atmoscope_eval::measured::run::{self, Settings};
use atmoscope_eval::measured::sky::{self, Aerosol, Site, Source};
use atmoscope_eval::measured::{broadband, score};

fn shipped_day() -> Day {
    let mut days =
        files::read_folder(&atmoscope_eval::measured::shipped_folder()).expect("the shipped day");
    days.remove(0)
}

fn settings(aerosol: AerosolSource) -> Settings {
    Settings {
        site: Site::CORNELL,
        aerosol: Some(aerosol),
        sources: Vec::new(),
        model_nm: run::default_model_nm(),
        fit_spp: 32,
        irradiance_strata: 6,
    }
}

/// The shipped day's scan 10 (noon), its measured spectra replaced by the path tracer's sky at
/// `aod550` (`spp` paths, a seed of its own) in every direction.
fn synthetic_day(aod550: f64, spp: u64) -> (Day, usize) {
    let mut day = shipped_day();
    let i = 10;
    let scan = day.scans[i].clone();
    let (_, sun_az) = run::sun_theory(&day, &scan, &Site::CORNELL);
    let aerosol = Aerosol {
        aod550,
        ..retrieve::shape(&day, &scan)
    };
    let scene = sky::scene(&day, &scan, &Site::CORNELL, &aerosol);
    let views: Vec<_> = (0..scan.directions.len())
        .map(|d| run::view_of(&scan, d, sun_az))
        .collect();
    let nm = day.wavelengths_nm.clone();
    let sky = sky::radiance(&scene, Source::PathTracer { spp, seed: 99 }, &views, &nm)
        .expect("the path tracer draws every scene");
    for (d, l) in day.scans[i].directions.iter_mut().zip(sky) {
        d.radiance = l;
    }
    (day, i)
}

/// The depth is the photometer's at the scan's UTC time, between the two records around it:
/// every record is given a depth of its own, so that another time (the local clock's, or the
/// weights the wrong way round) gives another depth.
#[test]
fn the_aeronet_retrieval_takes_the_photometer_s_depth_at_the_scan_s_time() {
    let mut day = shipped_day();
    let scan = day.scans[0].clone();
    for (k, r) in day.aeronet.iter_mut().enumerate() {
        r.tau440 = 0.1 + 0.05 * k as f64;
        r.angstrom = 1.4;
    }
    let t = scan.time_utc.seconds;
    let after = day
        .aeronet
        .iter()
        .position(|r| r.time_utc.seconds > t)
        .expect("a record after the scan");
    assert!(after > 0, "a record before the scan");
    let (a, b) = (&day.aeronet[after - 1], &day.aeronet[after]);
    let w = (t - a.time_utc.seconds) / (b.time_utc.seconds - a.time_utc.seconds);
    assert!((0.05..0.95).contains(&w), "the scan lies at a record: {w}");
    let tau440 = a.tau440 + w * (b.tau440 - a.tau440);
    let got = retrieve::from_aeronet(&day, &scan).expect("records");
    let want = tau440 * (550.0_f64 / 440.0).powf(-1.4);
    assert!(
        (got.aerosol.aod550 - want).abs() < 1e-12,
        "{} against {want}",
        got.aerosol.aod550
    );
    assert!((got.aerosol.angstrom - 1.4).abs() < 1e-12);
    day.aeronet.clear();
    assert!(retrieve::from_aeronet(&day, &scan).is_err());
}

#[test]
fn the_pyranometer_retrieval_finds_the_depth_of_a_synthetic_irradiance() {
    let mut day = shipped_day();
    let i = 5;
    let scan = day.scans[i].clone();
    let truth = Aerosol {
        aod550: 0.23,
        ..retrieve::shape(&day, &scan)
    };
    let scene = sky::scene(&day, &scan, &Site::CORNELL, &truth);
    let ghi = broadband::global(&retrieve::broadband_inputs(&scene, &Site::CORNELL, &truth))
        .expect("sun up");
    day.pyranometer = vec![GhiSample {
        time_local: scan.time_local,
        ghi_w_m2: ghi,
    }];
    let got = retrieve::from_pyranometer(&day, i, &Site::CORNELL).expect("a reading");
    assert!(
        (got.aerosol.aod550 - 0.23).abs() < 1e-6,
        "{}",
        got.aerosol.aod550
    );
    day.pyranometer.clear();
    assert!(retrieve::from_pyranometer(&day, i, &Site::CORNELL).is_err());
}

/// From the sky alone an aerosol's optical depth trades against its albedo (a brighter, thinner
/// aerosol scatters as much light), and the misfit is rough on the scale of the path tracer's
/// noise: the fit is held to the truth's depth and to a misfit within 10 % of the truth's.
#[test]
fn the_fit_finds_the_depth_of_a_path_traced_sky_within_0_03() {
    for aod in [0.08, 0.3] {
        let (day, i) = synthetic_day(aod, 64);
        let settings = settings(AerosolSource::Fit);
        let result = run::evaluate(&day, i, &settings).expect("a fit");
        let got = &result.retrieved.aerosol;
        assert!(
            (got.aod550 - aod).abs() < 0.03,
            "AOD {aod}: fitted {}",
            got.aod550
        );

        let scan = &day.scans[i];
        let (views, measured) =
            run::fit_spectra(&day, scan, &result.fitted_on, result.sun_azimuth_deg);
        let misfit = |aerosol: &Aerosol| {
            let scene = sky::scene(&day, scan, &Site::CORNELL, aerosol);
            retrieve::fit_misfit(&scene, &views, &measured, settings.fit_spp)
        };
        let truth = Aerosol {
            aod550: aod,
            ..retrieve::shape(&day, scan)
        };
        let (fitted, at_truth) = (misfit(got), misfit(&truth));
        assert!(
            fitted <= at_truth * 1.1,
            "AOD {aod}: the fit's misfit {fitted:.3e} against the truth's {at_truth:.3e}"
        );
    }
}

#[test]
fn the_fit_never_scores_a_direction_it_was_fitted_on() {
    let day = shipped_day();
    let i = 3;
    let settings = settings(AerosolSource::Fit);
    let result = run::evaluate(&day, i, &settings).expect("a fit");
    assert!(!result.fitted_on.is_empty() && !result.scored.is_empty());
    assert!(
        result.scored.iter().all(|d| !result.fitted_on.contains(d)),
        "a direction in both halves"
    );

    // Whatever the held-out half holds, the fit comes out the same: it never reads it.
    let mut poisoned = day.clone();
    for &d in &result.scored {
        for l in &mut poisoned.scans[i].directions[d].radiance {
            *l *= 50.0;
        }
    }
    let fit = |day: &Day| {
        run::retrieve(
            day,
            i,
            AerosolSource::Fit,
            &settings,
            &result.fitted_on,
            result.sun_azimuth_deg,
        )
        .expect("a fit")
        .aerosol
        .aod550
    };
    assert_eq!(fit(&day), fit(&poisoned));
    // The evaluation's own fit is that one, on that half.
    assert_eq!(result.retrieved.aerosol.aod550, fit(&day));
    // And what it is scored on is the held-out half alone, of the directions that are scored:
    // not the sample every scan reads wrong, none near the sun, and some near it left out
    // (the sun is up in the scan's sky).
    let scan = &day.scans[i];
    let (zenith, _) = run::sun_theory(&day, scan, &Site::CORNELL);
    let usable = score::scored_directions(scan, zenith, result.sun_azimuth_deg);
    assert_eq!(result.scored, score::Split::alternate(&usable).score);
    // The angle from the sun by this test's own arithmetic, not the scorer's, so that a slip in
    // the scorer's geometry shows.
    let unit = |elevation: f64, azimuth: f64| {
        let (e, a) = (elevation.to_radians(), azimuth.to_radians());
        [e.cos() * a.sin(), e.cos() * a.cos(), e.sin()]
    };
    let sun = unit(90.0 - zenith, result.sun_azimuth_deg);
    let from_sun_deg = |d: &files::Direction| {
        let v = unit(d.elevation_deg, d.azimuth_deg);
        let cos = v[0] * sun[0] + v[1] * sun[1] + v[2] * sun[2];
        cos.clamp(-1.0, 1.0).acos().to_degrees()
    };
    let near_sun = scan
        .directions
        .iter()
        .filter(|d| from_sun_deg(d) <= score::SUN_EXCLUSION_DEG)
        .count();
    assert!(near_sun > 0, "no direction near the sun to leave out");
    let bad = scan
        .directions
        .iter()
        .filter(|d| d.sample == score::BAD_SAMPLE)
        .collect::<Vec<_>>();
    assert!(bad.len() == 1 && from_sun_deg(bad[0]) > score::SUN_EXCLUSION_DEG);
    for &d in &usable {
        let direction = &scan.directions[d];
        assert_ne!(
            direction.sample,
            score::BAD_SAMPLE,
            "the bad sample is scored"
        );
        assert!(
            from_sun_deg(direction) > score::SUN_EXCLUSION_DEG,
            "direction {d} is scored near the sun"
        );
    }
    assert_eq!(usable.len(), scan.directions.len() - 1 - near_sun);
}

#[test]
fn the_sun_s_azimuth_of_a_path_traced_sky_is_its_own() {
    let (day, i) = synthetic_day(0.15, 32);
    let scan = &day.scans[i];
    let (_, theory) = run::sun_theory(&day, scan, &Site::CORNELL);
    let got = run::sun_azimuth_from_symmetry(&day, scan, theory + 8.0);
    assert!(
        (got - theory).abs() < 1.0,
        "theory {theory}°, from the symmetry {got}°"
    );
}

#[test]
fn the_project_s_sun_agrees_with_noaa_s_in_the_scan_list() {
    // The scan list carries the sun by NOAA's formulas: a check on the project's own code,
    // which places the sun from the scan's time and the site.
    let day = shipped_day();
    let list = std::fs::read_to_string(
        atmoscope_eval::measured::shipped_folder().join("scans_2013-05-27.csv"),
    )
    .expect("the scan list");
    let noaa: Vec<(f64, f64)> = list
        .lines()
        .skip(1)
        .map(|l| {
            let c: Vec<f64> = l
                .split(',')
                .skip(3)
                .map(|x| x.parse().expect("a number"))
                .collect();
            (c[0], c[1])
        })
        .collect();
    assert_eq!(noaa.len(), day.scans.len());
    for (scan, (zenith, azimuth)) in day.scans.iter().zip(noaa) {
        let (z, a) = run::sun_theory(&day, scan, &Site::CORNELL);
        assert!(
            (z - zenith).abs() < 0.02 && (a - azimuth).abs() < 0.05,
            "{}: {z} {a} against {zenith} {azimuth}",
            scan.time_local
        );
    }
}
