//! The presets shipped in `presets/`, embedded at build time.

use atmoscope_model::{Scene, SceneError};
use std::path::Path;

include!(concat!(env!("OUT_DIR"), "/presets.rs"));

/// The shipped preset the explorer opens on when there is no last session and no scene on
/// the command line: a view chosen to show what the app is for.
pub const FIRST_SCENE: &str = "golden-hour.ron";

/// The explorer's first scene (`FIRST_SCENE`); the built-in default scene should it not load.
pub fn first_scene() -> Scene {
    load_shipped(FIRST_SCENE)
        .and_then(Result::ok)
        .unwrap_or_default()
}

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

    #[test]
    fn the_first_scene_is_the_shipped_one() {
        let shipped = load_shipped(FIRST_SCENE).expect("listed").expect("valid");
        assert_eq!(first_scene(), shipped);
        assert_ne!(shipped, Scene::default());
    }
}
