//! The view suite: named views (camera, sun, projection, exposure, sizes) used by the benchmark,
//! the reference renders and the tests. The data lives in `presets/views/suite.ron`.

use crate::camera::Projection;
use crate::scene::{CameraSettings, Scene, SunSettings};
use serde::{Deserialize, Serialize};
use std::sync::OnceLock;

/// One named view.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct View {
    pub name: String,
    pub description: String,
    pub camera: CameraSettings,
    pub sun: SunSettings,
    pub projection: Projection,
    /// Exposure for display, EV.
    pub exposure_ev: f64,
    /// Full resolution (width, height).
    pub size: (u32, u32),
    /// Small resolution for CI.
    pub ci_size: (u32, u32),
}

impl View {
    /// `base` seen through this view.
    pub fn apply(&self, base: &Scene) -> Scene {
        let mut s = base.clone();
        s.camera = self.camera.clone();
        s.sun = self.sun;
        s.display.exposure_ev = self.exposure_ev;
        s.name = format!("{} · {}", base.name, self.name);
        s
    }
}

/// Every view of the suite, parsed once from the embedded data file.
pub fn suite() -> &'static [View] {
    static SUITE: OnceLock<Vec<View>> = OnceLock::new();
    SUITE.get_or_init(|| {
        ron::from_str(include_str!("../../presets/views/suite.ron"))
            .unwrap_or_else(|e| panic!("presets/views/suite.ron: {e}"))
    })
}

/// A view by name.
pub fn find(name: &str) -> Option<&'static View> {
    suite().iter().find(|v| v.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_suite_has_leenmans_and_garcia_linans_views_all_valid() {
        let s = suite();
        assert_eq!(s.len(), 21);
        for v in s {
            let scene = v.apply(&Scene::default());
            scene
                .validate()
                .unwrap_or_else(|e| panic!("{}: {e:?}", v.name));
            assert!(v.ci_size.0 <= v.size.0 && v.ci_size.1 <= v.size.1);
        }
        for name in [
            "ground-dawn",
            "orbit-noon",
            "space",
            "shadow-200km",
            "fisheye-sun-minus2",
            "twilight-12",
        ] {
            assert!(find(name).is_some(), "{name}");
        }
        let mut names: Vec<_> = s.iter().map(|v| &v.name).collect();
        names.sort();
        names.dedup();
        assert_eq!(names.len(), s.len(), "names are unique");
    }
}
