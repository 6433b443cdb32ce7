//! Every view of the suite renders at its CI size with finite, non-negative radiance, and the
//! sunlit views show light.

use atmoscope_model::Scene;
use atmoscope_model::methods::path_tracer::PathTracerSettings;
use atmoscope_model::reference::ReferenceRender;
use atmoscope_model::views;
use std::sync::atomic::AtomicBool;

#[test]
fn every_view_renders_at_ci_size() {
    let never = AtomicBool::new(false);
    for view in views::suite() {
        let scene = view.apply(&Scene::default());
        // A quarter of the CI size keeps this test short; the full CI size runs in the benchmark.
        let (w, h) = ((view.ci_size.0 / 4).max(4), (view.ci_size.1 / 4).max(4));
        let mut r = ReferenceRender::new(
            &scene,
            view.projection,
            w,
            h,
            1,
            PathTracerSettings::default(),
        );
        r.run_pass(2, &never);
        let rgb = r.linear_srgb();
        assert!(
            rgb.iter().flatten().all(|v| v.is_finite()),
            "{}: non-finite radiance",
            view.name
        );
        // Linear sRGB may dip slightly below zero for saturated colours; XYZ may not.
        assert!(
            r.pixels().iter().all(|p| p.xyz().y >= 0.0),
            "{}: negative luminance",
            view.name
        );
        if scene.sun.angles().elevation_deg > 0.0 {
            assert!(
                r.pixels().iter().any(|p| p.xyz().y > 0.0),
                "{}: black in daylight",
                view.name
            );
        }
    }
}
