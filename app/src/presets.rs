//! The presets shipped in `presets/`, embedded at build time.

use atmoscope_model::{Scene, SceneError};
use std::path::Path;

include!(concat!(env!("OUT_DIR"), "/presets.rs"));

/// Parses and validates one shipped preset by file name.
pub fn load_shipped(name: &str) -> Option<Result<Scene, SceneError>> {
    SHIPPED
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(n, text)| Scene::from_ron(text, &Path::new("presets").join(n)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn at_least_ten_presets_ship_and_each_parses_round_trips_and_validates() {
        assert!(SHIPPED.len() >= 10, "only {} presets", SHIPPED.len());
        for (name, _) in SHIPPED {
            let scene = load_shipped(name)
                .expect("listed")
                .unwrap_or_else(|e| panic!("{e}"));
            assert!(
                !scene.name.is_empty() && !scene.description.is_empty(),
                "{name} needs a name and description"
            );
            let again =
                Scene::from_ron(&scene.to_ron(), Path::new(name)).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(again, scene, "{name} does not round-trip");
        }
    }
}
