//! Export of the scene's atmosphere to the engines artists use: bevy's `Atmosphere`, Unreal's
//! SkyAtmosphere and Blender's Sky Texture (multiple scattering), each written as the snippet
//! its user pastes, read back, and drawn by our Hillaire model to say how close the engine can
//! come to the scene's full physics (`fidelity`).

pub mod bevy;
pub mod blender;
pub mod unreal;

use anyhow::Context;
use atmoscope_eval::metrics::{DisplaySetup, compare};
use atmoscope_model::Scene;
use atmoscope_model::atmosphere::Atmosphere;
use atmoscope_model::camera::Camera;
use atmoscope_model::engine_atmosphere::EngineAtmosphere;
use atmoscope_model::methods::shared::optics::{Params, viewpoint};
use atmoscope_model::methods::{self, SkyModel};
use atmoscope_model::scene::{Method, WavelengthSet};
use atmoscope_model::views::View;
use rayon::prelude::*;

/// The engines.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, clap::ValueEnum)]
pub enum Target {
    /// bevy 0.16–0.17's `Atmosphere` component, as Rust.
    Bevy,
    /// Unreal Engine's SkyAtmosphere component, its properties as JSON.
    Unreal,
    /// Blender 5's Sky Texture node (Multiple Scattering), as a Python script.
    Blender,
}

impl Target {
    pub const ALL: [Target; 3] = [Target::Bevy, Target::Unreal, Target::Blender];

    pub fn label(self) -> &'static str {
        match self {
            Target::Bevy => "bevy Atmosphere",
            Target::Unreal => "Unreal SkyAtmosphere",
            Target::Blender => "Blender Sky Texture",
        }
    }

    /// The written file's extension.
    pub fn extension(self) -> &'static str {
        match self {
            Target::Bevy => "rs",
            Target::Unreal => "json",
            Target::Blender => "py",
        }
    }

    /// The snippet for `scene`.
    pub fn write(self, scene: &Scene) -> String {
        let atm = Atmosphere::for_scene(scene);
        match self {
            Target::Bevy => bevy::write(&EngineAtmosphere::fit(&atm), &scene.name),
            Target::Unreal => unreal::write(&EngineAtmosphere::fit(&atm), &scene.name),
            Target::Blender => blender::write(&blender::BlenderSky::fit(scene, &atm), &scene.name),
        }
    }

    /// What the engine receives from a snippet this target wrote (a user may have edited it).
    pub fn read(self, text: &str) -> anyhow::Result<Exported> {
        Ok(match self {
            Target::Bevy => Exported::Exponential(bevy::read(text).context("bevy snippet")?),
            Target::Unreal => {
                Exported::Exponential(unreal::read(text).context("Unreal properties")?)
            }
            Target::Blender => Exported::Blender(blender::read(text).context("Blender script")?),
        })
    }
}

/// An engine's atmosphere as read back from its snippet.
#[derive(Debug, Clone, PartialEq)]
pub enum Exported {
    /// Hillaire's parameterisation (bevy, Unreal).
    Exponential(EngineAtmosphere),
    /// Blender's densities over its built-in physics.
    Blender(blender::BlenderSky),
}

impl Exported {
    /// The optics the engine's atmosphere gives at `scene`'s sun and camera, for a real-time
    /// model: at the engine's own colour sampling (RGB at 680/550/440 nm for bevy and Unreal,
    /// four wavelengths for Blender).
    pub fn params(&self, scene: &Scene) -> Params {
        match self {
            Exported::Exponential(e) => {
                let atm = Atmosphere::new(&scene.atmosphere);
                let base = Params::new(&atm, self.colours(), scene.render.quality);
                e.params(&base)
            }
            Exported::Blender(b) => {
                let s = b.scene(scene);
                let atm = Atmosphere::new(&s.atmosphere);
                Params::new(&atm, self.colours(), s.render.quality)
            }
        }
    }

    /// The engine's colour sampling: RGB at 680/550/440 nm, or four wavelengths (Blender).
    pub fn colours(&self) -> WavelengthSet {
        match self {
            Exported::Exponential(_) => WavelengthSet::Rgb3,
            Exported::Blender(_) => WavelengthSet::Spectral4,
        }
    }

    /// The scene the engine's atmosphere draws in: Blender's planet, or the scene's.
    fn geometry(&self, scene: &Scene) -> Scene {
        match self {
            Exported::Exponential(_) => scene.clone(),
            Exported::Blender(b) => b.scene(scene),
        }
    }
}

/// How far one view of the suite drawn with the engine's atmosphere lies from the scene's
/// full physics.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewError {
    pub view: String,
    /// The engine's parameters at its colour sampling against the full physics.
    pub delta_e2000_mean: f64,
    pub delta_e2000_p95: f64,
    /// The full physics at the engine's colour sampling against the full physics: the part
    /// of the error that the engine's colours alone make, whatever its parameters.
    pub colours_delta_e2000_mean: f64,
}

/// The wavelength set of the full physics the exports are measured against.
pub const FULL_PHYSICS: WavelengthSet = WavelengthSet::SpectralN(16);

/// Image size of each view of the comparison, pixels.
pub const FIDELITY_SIZE: (u32, u32) = (64, 36);

/// ΔE2000 between the scene drawn by Hillaire's model with its full physics (`FULL_PHYSICS`)
/// and with the engine's atmosphere, over the `views` (the view suite's, which the CLI and
/// the window measure) that the model draws: the scene's atmosphere, the view's camera and
/// sun, displayed with the view's exposure and the scene's tone map. `go_on` is told each
/// view's name as it starts; where it answers false (the work was cancelled) the view is
/// left out.
pub fn fidelity(
    scene: &Scene,
    exported: &Exported,
    views: &[View],
    go_on: &(dyn Fn(&str) -> bool + Sync),
) -> Vec<ViewError> {
    let hillaire = methods::info(Method::Hillaire);
    let Some(build) = hillaire.build else {
        return Vec::new();
    };
    let (w, h) = FIDELITY_SIZE;
    views
        .par_iter()
        .filter_map(|view| {
            let mut full = view.apply(scene);
            full.render.method = Method::Hillaire;
            full.render.wavelengths = FULL_PHYSICS;
            if !go_on(&view.name) {
                return None;
            }
            let reference = methods::render(&full, view.projection, w, h).ok()?;
            let mut sampled = full.clone();
            sampled.render.wavelengths = exported.colours();
            let colours_only = methods::render(&sampled, view.projection, w, h).ok()?;
            let engine_scene = exported.geometry(&full);
            let engine_camera = Camera::new(
                &engine_scene.camera,
                engine_scene.atmosphere.planet_radius_km * 1000.0,
                view.projection,
            );
            let params = exported
                .params(&engine_scene)
                .with_render(&engine_scene.render);
            let model: Box<dyn SkyModel> = build(&params, viewpoint(&engine_scene, &engine_camera));
            let drawn = methods::render_with(model.as_ref(), &engine_scene, &engine_camera, w, h);
            let setup = DisplaySetup {
                exposure_ev: full.display.exposure_ev,
                tone_map: full.display.tone_map,
                ..DisplaySetup::default()
            };
            let (c, _) = compare(&drawn, &reference, w, h, setup);
            let (colours, _) = compare(&colours_only, &reference, w, h, setup);
            Some(ViewError {
                view: view.name.clone(),
                delta_e2000_mean: c.delta_e2000_mean,
                delta_e2000_p95: c.delta_e2000_p95,
                colours_delta_e2000_mean: colours.delta_e2000_mean,
            })
        })
        .collect()
}

/// The mean over the views of each view's mean ΔE2000: the engine's parameters, and its
/// colours alone.
pub fn mean_delta_e(errors: &[ViewError]) -> (f64, f64) {
    let n = errors.len().max(1) as f64;
    (
        errors.iter().map(|e| e.delta_e2000_mean).sum::<f64>() / n,
        errors
            .iter()
            .map(|e| e.colours_delta_e2000_mean)
            .sum::<f64>()
            / n,
    )
}

/// The errors as a Markdown table with their means.
pub fn fidelity_table(target: Target, errors: &[ViewError]) -> String {
    let mut s = format!(
        "{}: ΔE2000 against the scene's full physics ({}), all drawn by Hillaire's model, {} views of the suite\n\n| view | engine's parameters: mean | p95 | its colours alone: mean |\n| --- | ---: | ---: | ---: |\n",
        target.label(),
        FULL_PHYSICS.label(),
        errors.len()
    );
    for e in errors {
        s += &format!(
            "| {} | {:.2} | {:.2} | {:.2} |\n",
            e.view, e.delta_e2000_mean, e.delta_e2000_p95, e.colours_delta_e2000_mean
        );
    }
    let (engine, colours) = mean_delta_e(errors);
    s += &format!("| mean | {engine:.2} | | {colours:.2} |\n");
    s
}

/// A number as the snippets write it, to seven significant digits or more: plain from 0.1 up
/// to 10⁷, in exponent form elsewhere.
fn number(v: f64) -> String {
    if v == 0.0 {
        "0.0".into()
    } else if (0.1..1e7).contains(&v.abs()) {
        let s = format!("{v:.7}");
        let s = s.trim_end_matches('0');
        if s.ends_with('.') {
            format!("{s}0")
        } else {
            s.to_string()
        }
    } else {
        format!("{v:.6e}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use atmoscope_model::aerosol::AerosolType;
    use atmoscope_model::profiles::{AirProfile, OzoneProfile};

    fn views() -> Vec<View> {
        [
            "ground-noon",
            "fisheye-sun10",
            "orbit-sunrise",
            "twilight-6",
        ]
        .iter()
        .map(|n| {
            atmoscope_model::views::find(n)
                .expect("in the suite")
                .clone()
        })
        .collect()
    }

    /// What each engine's snippet says, read back and drawn, is the atmosphere it was written
    /// for where the engine can hold that atmosphere whole: exponential air and aerosol with
    /// a tent of ozone for bevy and Unreal, Blender's own Earth for Blender. Their ΔE2000 over
    /// its colours alone is then under 0.3 (what is left: the 8-bit ground of Unreal, the
    /// depolarisation the engines leave out).
    #[test]
    fn each_export_reads_back_to_the_atmosphere_it_was_written_for() {
        let mut exponential = Scene::default();
        let a = &mut exponential.atmosphere;
        a.air_profile = AirProfile::Exponential8km;
        a.ozone.profile = OzoneProfile::Tent;
        a.aerosol.kind = AerosolType::Custom;
        a.aerosol.custom.angstrom_exponent = 0.0;
        a.aerosol.custom.scale_height_km = 1.2;
        let blender_earth = blender::BlenderSky::EARTH.scene(&Scene::default());
        for (target, scene) in [
            (Target::Bevy, &exponential),
            (Target::Unreal, &exponential),
            (Target::Blender, &blender_earth),
        ] {
            let exported = target.read(&target.write(scene)).expect("reads back");
            let errors = fidelity(scene, &exported, &views(), &|_| true);
            assert_eq!(errors.len(), 4, "{target:?}");
            let (engine, colours) = mean_delta_e(&errors);
            eprintln!("{}", fidelity_table(target, &errors));
            assert!(
                engine - colours < 0.3,
                "{target:?}: {engine:.2} against {colours:.2}"
            );
        }
    }
}
