//! What changed since the last frame: the scene's inputs as a snapshot, compared field by
//! field into the set of `Inputs` that changed.

use super::*;

#[derive(Debug, Clone, PartialEq)]
pub(super) struct AtmosphereKey {
    pub(super) settings: AtmosphereSettings,
    pub(super) method: Method,
    pub(super) wavelengths: WavelengthSet,
    pub(super) quality: Quality,
    pub(super) scattering_orders: u32,
    pub(super) fitted_constants: FittedConstants,
    /// The CIE sky type where the model draws one (`render.cie_sky_type`), so that another
    /// model's tables do not rebuild when it changes.
    pub(super) cie_sky_type: Option<u8>,
}

impl AtmosphereKey {
    /// The key with the ground's albedo and type left out (`Inputs::GROUND_ALBEDO` apart).
    pub(super) fn without_albedo(&self) -> AtmosphereKey {
        let mut k = self.clone();
        k.settings.ground_albedo = 0.0;
        k.settings.ground = atmoscope_model::ground::GroundType::Grey;
        k
    }
}

#[derive(Debug, Clone, PartialEq)]
pub(super) struct Snapshot {
    /// The atmosphere's key without the ground, which is apart.
    pub(super) atmosphere: AtmosphereKey,
    /// The ground's type and grey albedo.
    pub(super) ground: (atmoscope_model::ground::GroundType, f64),
    pub(super) viewpoint: [f64; 2],
    /// The sun's direction and the scale of its light (`SunSettings::sunlight_scale`).
    pub(super) sun: [f64; 4],
    pub(super) camera: (CameraSettings, Projection, bool),
    pub(super) size: [u32; 2],
    pub(super) display: (f64, ToneMap, DisplayMode, bool, WhiteBalance, bool),
}

impl Snapshot {
    pub(super) fn changes_from(&self, previous: Option<&Snapshot>) -> Inputs {
        let Some(p) = previous else {
            return Inputs::ALL;
        };
        let mut c = Inputs::NONE;
        let mut mark = |changed: bool, i: Inputs| {
            if changed {
                c = c.union(i);
            }
        };
        mark(self.atmosphere != p.atmosphere, Inputs::ATMOSPHERE);
        mark(self.ground != p.ground, Inputs::GROUND_ALBEDO);
        mark(self.viewpoint != p.viewpoint, Inputs::VIEWPOINT);
        mark(self.sun != p.sun, Inputs::SUN);
        mark(self.camera != p.camera, Inputs::CAMERA);
        mark(self.size != p.size, Inputs::VIEW_SIZE);
        mark(self.display != p.display, Inputs::DISPLAY);
        c
    }
}
