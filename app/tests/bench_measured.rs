//! `atmoscope bench measured` from the command line: the JSON it promises on the shipped day,
//! the files `--out` writes, and a damaged folder refused with its file and line.

use std::process::{Command, Output};

fn atmoscope(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_atmoscope"))
        .args(args)
        .output()
        .expect("run atmoscope")
}

#[test]
fn one_scan_of_the_shipped_day_gives_the_promised_json_and_files() {
    let out = tempfile::tempdir().expect("temporary folder");
    let o = atmoscope(&[
        "bench",
        "measured",
        "--scans",
        "12:00",
        "--models",
        "preetham,path-tracer",
        "--spp",
        "32",
        "--json",
        "--out",
        out.path().to_str().expect("a UTF-8 path"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).expect("one JSON object");
    let scan = &v["scans"][0];
    assert_eq!(scan["date"], "2013-05-27");
    assert_eq!(scan["time_local"], "12:00");
    assert_eq!(
        scan["aerosol"]["source"], "aeronet",
        "the day has an AERONET file"
    );
    for key in [
        "sun_zenith_deg",
        "sun_azimuth_deg",
        "sun_azimuth_theory_deg",
    ] {
        assert!(
            scan[key].as_f64().is_some_and(f64::is_finite),
            "{key}: {}",
            scan[key]
        );
    }
    for key in ["aod550", "angstrom"] {
        assert!(
            scan["aerosol"][key].as_f64().is_some_and(|x| x > 0.0),
            "{key}"
        );
    }
    // The depth is AERONET's at the scan's time.
    let days =
        atmoscope_eval::measured::files::read_folder(&atmoscope_eval::measured::shipped_folder())
            .expect("the shipped day");
    let noon = days[0]
        .scans
        .iter()
        .find(|s| s.time_local.seconds == 12.0 * 3600.0)
        .expect("the 12:00 scan");
    let aeronet = atmoscope_eval::measured::retrieve::from_aeronet(&days[0], noon)
        .expect("records")
        .aerosol
        .aod550;
    let aod550 = scan["aerosol"]["aod550"].as_f64().expect("aod550");
    assert!(
        (aod550 - aeronet).abs() < 1e-12,
        "{aod550} against AERONET's {aeronet}"
    );
    // Of the scan's 81 directions, the bad sample and those within 10° of the sun (24.9° from
    // the zenith at noon) are not scored.
    let scored = scan["directions_scored"]
        .as_u64()
        .expect("directions_scored");
    assert!((70..80).contains(&scored), "{scored} directions scored");
    let ids: Vec<&str> = v["models"]
        .as_array()
        .expect("models")
        .iter()
        .map(|m| m["id"].as_str().expect("id"))
        .collect();
    assert_eq!(ids, ["preetham", "path-tracer"]);
    for m in v["models"].as_array().expect("models") {
        for key in [
            "radiance_median_abs_rel_err",
            "radiance_p95_abs_rel_err",
            "luminance_median_abs_rel_err",
        ] {
            assert!(
                m[key].as_f64().is_some_and(|x| (0.0..10.0).contains(&x)),
                "{key}: {}",
                m[key]
            );
        }
        // 360–720 nm at 10 nm over the scan's scored directions.
        assert_eq!(m["samples"].as_u64(), Some(37 * scored));
    }
    for file in [
        "measured.md",
        "measured.json",
        "scan_2013-05-27_1200.csv",
        "day_zenith_luminance.png",
        "spectra_1.png",
        "dome_preetham.png",
    ] {
        assert!(out.path().join(file).is_file(), "{file} was not written");
    }
}

#[test]
fn a_damaged_folder_is_refused_with_its_file_and_line() {
    let dir = tempfile::tempdir().expect("temporary folder");
    std::fs::write(
        dir.path().join("radiance_2013-05-27.csv"),
        "date,time_local_edt,time_utc,sample,azimuth_deg,elevation_deg,L350\n2013-05-27,09:30,13:30,0,0,12.1,bad\n",
    )
    .expect("write");
    let o = atmoscope(&[
        "bench",
        "measured",
        "--data",
        dir.path().to_str().expect("a UTF-8 path"),
    ]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("radiance_2013-05-27.csv:2: L350: `bad` is not a finite number"),
        "{err}"
    );
    let o = atmoscope(&["bench", "measured", "--aerosol", "sunshine"]);
    assert!(
        String::from_utf8_lossy(&o.stderr)
            .contains("no aerosol source `sunshine` (aeronet, pyranometer, fit)")
    );
}
