//! Every model of the registry keeps the accuracy it states, in the fast tier: each real-time
//! model's f64 CPU twin, probed as `atmoscope probe` does, in the hazy daylight sky its bound
//! is stated for (the built-in default scene: rural aerosol, AOD 0.15, sun 30° up, camera on
//! the ground), against the path tracer. A model added to the registry is covered without an
//! edit here. The research tier holds each model over the whole view suite as well.

use atmoscope::cli::sky_probe::{self, ProbeMethod, ProbeRequest};
use atmoscope_model::Scene;
use atmoscope_model::methods;

/// Two directions (the zenith, and 60° from it at 120° from the sun) at 450 and 650 nm, where
/// the registry's bounds were measured.
fn request(method: ProbeMethod, spp: u64) -> ProbeRequest {
    ProbeRequest {
        view_zenith_deg: vec![0.0, 60.0],
        view_azimuth_deg: vec![120.0],
        wavelengths_nm: vec![450.0, 650.0],
        method,
        max_order: None,
        spp,
        seed: 1,
        stokes: false,
    }
}

fn radiances(scene: &Scene, method: ProbeMethod, spp: u64) -> Vec<(f64, f64)> {
    sky_probe::probe(scene, &request(method, spp))
        .samples
        .iter()
        .map(|s| {
            (
                s.radiance,
                s.std_error * s.radiance / s.radiance_per_irradiance,
            )
        })
        .collect()
}

#[test]
fn every_model_keeps_its_stated_error_of_the_path_tracer_in_a_hazy_daylight_sky() {
    let scene = Scene::default();
    // 8 192 paths: a standard error near 1.2 % on each value. The bound is widened by three
    // of the path tracer's standard errors, so that its noise alone fails no model.
    let truth = radiances(&scene, ProbeMethod::PathTracer, 8192);
    let mut failures = Vec::new();
    let mut checked = 0;
    for model in methods::realtime() {
        let values = radiances(&scene, ProbeMethod::Model(model.method), 1);
        assert_eq!(values.len(), truth.len(), "{}", model.id);
        // A model that states no bound draws no sky: black.
        let Some(bound) = model.stated.probe_relative_error else {
            assert!(
                values.iter().all(|&(v, _)| v == 0.0),
                "{} states no error, so it should draw no sky: {values:?}",
                model.id
            );
            continue;
        };
        for (&(v, _), &(t, se)) in values.iter().zip(&truth) {
            let error = (v / t - 1.0).abs();
            // Written so that a NaN fails too.
            if !(error < bound + 3.0 * se / t) {
                failures.push(format!(
                    "{}: {v:.4e} against the path tracer's {t:.4e} ± {se:.1e}: {:.1} % off, stated {:.0} %",
                    model.id,
                    100.0 * error,
                    100.0 * bound
                ));
            }
        }
        checked += 1;
    }
    assert!(checked > 0, "no model states an error");
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
