//! The measured-sky reader against hand-made folders: a good day read whole, and each kind of
//! damage answered with the file, the line and what is wrong, with nothing half-read.

use atmoscope_eval::measured::files::{self, MeasuredError};
use std::path::Path;

const HEADER: &str = "date,time_local_edt,time_utc,sample,azimuth_deg,elevation_deg,L350,L355,L360";

fn radiance_rows() -> Vec<String> {
    let mut rows = vec![HEADER.to_owned()];
    for (local, utc) in [("09:30", "13:30"), ("09:45", "13:45")] {
        for (sample, az, el) in [(0, 0.0, 12.1151), (1, 348.75, 12.1151), (2, 0.0, 90.0)] {
            // Each direction its own spectrum, so that rows or columns read in the wrong
            // place show.
            let l = 0.05 + 0.1 * f64::from(sample);
            rows.push(format!(
                "2013-05-27,{local},{utc},{sample},{az},{el},{l:.2},{:.2},{:.2}",
                l + 0.01,
                l + 0.02
            ));
        }
    }
    rows
}

fn write(dir: &Path, name: &str, rows: &[String]) {
    std::fs::write(dir.join(name), rows.join("\n") + "\n").expect("temporary folder");
}

/// A folder holding one good day, with its pyranometer and AERONET files.
fn good_folder() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("temporary folder");
    write(dir.path(), "radiance_2013-05-27.csv", &radiance_rows());
    write(
        dir.path(),
        "scans_2013-05-27.csv",
        &[
            "date,time_local_edt,time_utc,sun_zenith_deg_noaa,sun_azimuth_deg_noaa".into(),
            "2013-05-27,09:30,13:30,48.937,98.139".into(),
            "2013-05-27,09:45,13:45,46.208,101.091".into(),
        ],
    );
    write(
        dir.path(),
        "pyranometer_2013-05-27.csv",
        &[
            "time_local_edt,global_horizontal_irradiance_w_m2".into(),
            "09:30:00,650.0".into(),
            "09:30:04,652.0".into(),
            "09:45:00,700.0".into(),
        ],
    );
    write(dir.path(), "site_2013-05-27.pfn", &aeronet_rows("0.12"));
    dir
}

/// The asymmetry parameters of the phase functions `aeronet_rows` writes at 442 and 674 nm.
const G_442_674: (f64, f64) = (0.70, 0.60);

fn aeronet_rows(tau440: &str) -> Vec<String> {
    // Henyey–Greenstein phase functions every 2.5°, of a g of their own at each band.
    let angles: Vec<f64> = (0..=72).map(|i| 2.5 * f64::from(i)).collect();
    let hg = |g: f64, theta: f64| {
        (1.0 - g * g) / (1.0 + g * g - 2.0 * g * theta.to_radians().cos()).powf(1.5)
    };
    let mut header = vec![
        "Date(dd-mm-yyyy)".to_owned(),
        "Time(hh:mm:ss)".into(),
        "Julian_Day".into(),
    ];
    for band in ["442nm", "674nm"] {
        header.extend(angles.iter().map(|a| format!("{a:.4}[{band}]")));
    }
    header.extend(["alpha440-870".into(), "tau440(measured)".into()]);
    let record = |time: &str| {
        let mut r = vec!["27:05:2013".to_owned(), time.into(), "147.5".into()];
        for g in [G_442_674.0, G_442_674.1] {
            r.extend(angles.iter().map(|&a| format!("{:.6}", hg(g, a))));
        }
        r.extend(["1.1".into(), tau440.into()]);
        r.join(",")
    };
    vec![
        "27:05:2013,Locations=Test".into(),
        "Level 1.5 Almucantar Retrievals, Version 2".into(),
        "Phase Functions".into(),
        header.join(","),
        record("13:00:00"),
        record("14:00:00"),
    ]
}

#[test]
fn a_good_folder_is_read_whole() {
    let dir = good_folder();
    let days = files::read_folder(dir.path()).expect("a good folder");
    assert_eq!(days.len(), 1);
    let day = &days[0];
    assert_eq!((day.year, day.month, day.day), (2013, 5, 27));
    assert_eq!(day.wavelengths_nm, [350.0, 355.0, 360.0]);
    assert_eq!(day.scans.len(), 2);
    assert_eq!(day.scans[0].directions.len(), 3);
    let d = &day.scans[0].directions[1];
    assert_eq!(
        (d.sample, d.azimuth_deg, d.elevation_deg),
        (1, 348.75, 12.1151)
    );
    assert_eq!(d.radiance, [0.15, 0.16, 0.17]);
    assert_eq!(day.scans[1].directions[2].radiance, [0.25, 0.26, 0.27]);
    assert!((day.scans[0].utc_offset_h() + 4.0).abs() < 1e-12);
    assert_eq!(day.ghi_during(0), Some(651.0));
    assert_eq!(day.ghi_during(1), Some(700.0));
    assert_eq!(day.aeronet.len(), 2);
    assert!((day.aeronet[0].aod550() - 0.12 * (550.0_f64 / 440.0).powf(-1.1)).abs() < 1e-12);
    let g = day.aeronet[0]
        .asymmetry_g
        .expect("phase functions at both bands");
    assert!(
        (g.0 - G_442_674.0).abs() < 0.02 && (g.1 - G_442_674.1).abs() < 0.02,
        "{g:?} against {G_442_674:?}"
    );
}

#[test]
fn the_optional_files_may_be_missing() {
    let dir = good_folder();
    std::fs::remove_file(dir.path().join("pyranometer_2013-05-27.csv")).expect("exists");
    std::fs::remove_file(dir.path().join("site_2013-05-27.pfn")).expect("exists");
    let days = files::read_folder(dir.path()).expect("still a good folder");
    assert!(days[0].pyranometer.is_empty() && days[0].aeronet.is_empty());
    assert_eq!(days[0].ghi_during(0), None);
}

/// Damages the good folder with `damage`, reads it and returns the error.
fn damaged(damage: impl FnOnce(&Path)) -> MeasuredError {
    let dir = good_folder();
    damage(dir.path());
    match files::read_folder(dir.path()) {
        Ok(days) => panic!("a damaged folder was read: {} days", days.len()),
        Err(e) => e,
    }
}

fn with_radiance_row(row: usize, text: &str) -> impl FnOnce(&Path) {
    let text = text.to_owned();
    move |dir: &Path| {
        let mut rows = radiance_rows();
        rows[row] = text;
        write(dir, "radiance_2013-05-27.csv", &rows);
    }
}

#[test]
fn each_damage_is_named_with_its_file_and_line() {
    let cases: Vec<(Box<dyn FnOnce(&Path)>, &str, Option<usize>, &str)> = vec![
        (
            Box::new(with_radiance_row(
                2,
                "2013-05-27,09:30,13:30,1,348.75,12.1151,0.05,oops,0.07",
            )),
            "radiance_2013-05-27.csv",
            Some(3),
            "L355: `oops` is not a finite number",
        ),
        (
            Box::new(with_radiance_row(
                2,
                "2013-05-27,09:30,13:30,1,348.75,12.1151,0.05,0.06",
            )),
            "radiance_2013-05-27.csv",
            Some(3),
            "8 cells where the header has 9",
        ),
        (
            Box::new(with_radiance_row(
                2,
                "2013-05-27,09:30,13:30,1,348.75,95,0.05,0.06,0.07",
            )),
            "radiance_2013-05-27.csv",
            Some(3),
            "elevation 0–90°",
        ),
        (
            Box::new(with_radiance_row(
                2,
                "2013-05-27,09:30,13:30,0,348.75,12.1151,0.05,0.06,0.07",
            )),
            "radiance_2013-05-27.csv",
            Some(3),
            "sample 0 of scan 09:30 appears twice",
        ),
        (
            Box::new(with_radiance_row(
                2,
                "2013-05-27,9h30,13:30,1,348.75,12.1151,0.05,0.06,0.07",
            )),
            "radiance_2013-05-27.csv",
            Some(3),
            "`9h30` is not a time of day",
        ),
        (
            Box::new(with_radiance_row(
                2,
                "2013-05-27,09:30,13:30,1,348.75,12.1151,0.05,NaN,0.07",
            )),
            "radiance_2013-05-27.csv",
            Some(3),
            "not a finite number",
        ),
        (
            Box::new(with_radiance_row(0, "date,time,sample,L350")),
            "radiance_2013-05-27.csv",
            Some(1),
            "the header must begin",
        ),
        (
            Box::new(|dir: &Path| {
                write(
                    dir,
                    "scans_2013-05-27.csv",
                    &[
                        "date,time_local_edt,time_utc".into(),
                        "2013-05-27,09:30,13:30".into(),
                    ],
                )
            }),
            "scans_2013-05-27.csv",
            None,
            "radiance_2013-05-27.csv has scan 09:45, which this list lacks",
        ),
        (
            Box::new(|dir: &Path| {
                std::fs::remove_file(dir.join("scans_2013-05-27.csv")).expect("exists")
            }),
            "scans_2013-05-27.csv",
            None,
            "cannot read",
        ),
        (
            Box::new(|dir: &Path| {
                write(
                    dir,
                    "pyranometer_2013-05-27.csv",
                    &[
                        "time_local_edt,global_horizontal_irradiance_w_m2".into(),
                        "09:30:00,-5".into(),
                    ],
                )
            }),
            "pyranometer_2013-05-27.csv",
            Some(2),
            "outside 0–2000",
        ),
        (
            Box::new(|dir: &Path| write(dir, "site_2013-05-27.pfn", &aeronet_rows("lots"))),
            "site_2013-05-27.pfn",
            Some(5),
            "tau440(measured): `lots` is not a number",
        ),
        (
            Box::new(|dir: &Path| write(dir, "site_2013-05-27.pfn", &["just text".into()])),
            "site_2013-05-27.pfn",
            None,
            "not an AERONET inversion file",
        ),
    ];
    for (damage, file, line, message) in cases {
        let e = damaged(damage);
        assert_eq!(
            e.file.file_name().and_then(|f| f.to_str()),
            Some(file),
            "{e}"
        );
        assert_eq!(e.line, line, "{e}");
        assert!(e.message.contains(message), "expected “{message}” in: {e}");
    }
}

#[test]
fn a_folder_without_days_says_what_it_lacks() {
    let dir = tempfile::tempdir().expect("temporary folder");
    let e = files::read_folder(dir.path()).expect_err("an empty folder");
    assert!(
        e.to_string().contains("no radiance_<yyyy-mm-dd>.csv here"),
        "{e}"
    );
    let e = files::read_folder(&dir.path().join("absent")).expect_err("no folder");
    assert!(e.to_string().contains("cannot read the folder"), "{e}");
}

#[test]
fn the_shipped_day_reads_as_its_readme_describes() {
    let days =
        files::read_folder(&atmoscope_eval::measured::shipped_folder()).expect("the shipped day");
    assert_eq!(days.len(), 1);
    let day = &days[0];
    assert_eq!(day.scans.len(), 15);
    assert!(day.scans.iter().all(|s| s.directions.len() == 81));
    assert_eq!(day.wavelengths_nm.first(), Some(&350.0));
    assert_eq!(day.wavelengths_nm.last(), Some(&830.0));
    assert!(!day.aeronet.is_empty());
    // The pyranometer's file stops before the last scan (13:30).
    assert!((0..14).all(|i| day.ghi_during(i).is_some()));
    assert_eq!(day.ghi_during(14), None);
}
