//! Elek (2009), "Rendering Parametrizable Planetary Atmospheres with Multiple Scattering in
//! Real-Time", as the Atmosphere Plus notes (J. Boody) describe it, following Bodare & Sandberg
//! (2014): the f64 CPU twin of the passes in `shaders/elek/`.
//!
//! Bruneton's 4D tables lose their fourth axis: the in-scattering of a texel (h, mu, mu_s) is
//! computed with the view and the sun in the same vertical half-plane (azimuth 0), and the
//! sun–view azimuth is ignored at look-up, where the phase functions are applied to the view–sun
//! angle. Rayleigh and Mie are stored apart, each without its phase function, so that the
//! look-up applies them; Rayleigh with the notes' modified phase 0.8·(1.4 + 0.5·cos θ)/(4π),
//! which darkens the sky opposite the sun to make up for the missing azimuth.
//!
//! Orders are gathered one by one ([`gather`], [`multiple_scattering`], [`accumulate`]): order
//! k of a texel is the previous order's table, looked up along every direction of the sphere at the local
//! altitude and angles (again without azimuth) and weighted by the phase function between that
//! direction and the view, integrated along the view ray. As the notes do, each order carries
//! the view's phase pulled out of it, Rayleigh feeds only Rayleigh and Mie only Mie, and the
//! ground reflects nothing into the sky (it is drawn lit by the sun alone). Without the azimuth
//! the Earth's shadow cannot appear in twilight: the domain is daylight.
//!
//! Departures, each recorded in docs/models/elek.md: the medium (profiles, cross-sections,
//! ozone, the aerosol phase function) is the scene's, as for every model; transmittance comes
//! from the shared table; integrals along a texel's ray use the shared placement that crowds
//! samples towards the ray's lowest point ([`crate::methods::shared::ray`]); the sphere is
//! integrated by the midpoint rule, and since the previous order does not depend on the
//! azimuth of a gathered direction, one look-up serves each zenith ring.
//!
//! From inside the atmosphere the sky reads the tables' rows at the camera ([`camera_slice`]),
//! the only tables that depend on the sun or the camera's altitude.

pub mod accumulate;
pub mod camera_slice;
pub mod gather;
pub mod multiple_scattering;
pub mod single_scattering;
pub mod sky;

use super::shared::ray::Coords;
use super::shared::transmittance::{self, compute_transmittance_lut};
use super::shared::{Lanes, Lut, Params, TableSpec, Viewpoint};
use super::{Domain, Inputs, SkyModel};
use crate::geometry::hits_ground;
use glam::DVec3;

/// View zenith cosine (mu) texels: x of the tables (the notes' 128).
pub const MU: u32 = 128;
/// Sun zenith cosine (mu_s) texels: y.
pub const MU_S: u32 = 32;
/// Altitude texels: z, the slices.
pub const H: u32 = 32;
/// The size of every scattering table (mu, mu_s, h).
pub const SIZE: [u32; 3] = [MU, MU_S, H];

/// Where the model is meant to work: from the ground to space in daylight. The tables cover the
/// sun below the horizon too, but without the sun–view azimuth the Earth's shadow cannot form.
pub const DOMAIN: Domain = Domain {
    max_altitude_m: f64::INFINITY,
    min_sun_elevation_deg: 0.0,
    note: "ground, plane and space views in daylight; without the sun–view azimuth the Earth's shadow in twilight cannot appear",
    max_aod550: 0.05,
    refuses: false,
};

pub(crate) const AXES: [&str; 3] = [
    "x: view zenith cosine μ, −1 (nadir, left) to 1 (zenith, right), cube-root spacing (dense at the horizontal)",
    "y: sun zenith cosine μ_s, −1 (top) to 1 (bottom), cube-root spacing",
    "z: altitude, ground (slice 0) to the top, square-root spacing",
];

fn describe(p: &Params, _: f64, [x, y, z]: [f64; 3]) -> String {
    let (h, mu, mu_s) = h_mu_mu_s_from_texel(p, [x, y, z]);
    format!(
        "h = {:.2} km, μ = {mu:.4}, μ_s = {mu_s:.4}{}",
        h / 1000.0,
        if hits_ground(h, mu, p.bottom_radius_m) {
            " (to the ground)"
        } else {
            ""
        }
    )
}

const fn table(id: &'static str, label: &'static str) -> TableSpec {
    TableSpec {
        id,
        label,
        size: SIZE,
        axes: AXES,
        invalidated_by: Inputs::ATMOSPHERE,
        transmittance: false,
        describe_texel: describe,
    }
}

/// Rayleigh in-scattering of every order, without its phase function.
pub const RAYLEIGH: TableSpec = table("rayleigh-scattering", "Rayleigh, all orders (no phase)");
/// Mie in-scattering of every order, without its phase function.
pub const MIE: TableSpec = table("mie-scattering", "Mie, all orders (no phase)");
/// The last order's Rayleigh part.
pub const DELTA_RAYLEIGH: TableSpec = table("delta-rayleigh", "Δ Rayleigh (last order)");
/// The last order's Mie part.
pub const DELTA_MIE: TableSpec = table("delta-mie", "Δ Mie (last order)");
/// The last order's Rayleigh part gathered over the sphere with the Rayleigh phase.
pub const GATHERED_RAYLEIGH: TableSpec =
    table("gathered-rayleigh", "gathered Rayleigh (last order)");
/// The last order's Mie part gathered over the sphere with the aerosol phase.
pub const GATHERED_MIE: TableSpec = table("gathered-mie", "gathered Mie (last order)");

/// Every table of the method, in pass order.
pub const TABLES: [TableSpec; 9] = [
    transmittance::TABLE,
    DELTA_RAYLEIGH,
    DELTA_MIE,
    RAYLEIGH,
    MIE,
    GATHERED_RAYLEIGH,
    GATHERED_MIE,
    camera_slice::CAMERA_RAYLEIGH,
    camera_slice::CAMERA_MIE,
];

/// The notes' cosine axis: ½(1 + sign(c)·|c|^⅓), dense where the cosine is near 0.
pub fn cosine_axis(c: f64) -> f64 {
    0.5 * (1.0 + c.clamp(-1.0, 1.0).cbrt())
}

/// The inverse of [`cosine_axis`]: (2v − 1)³.
pub fn cosine_from_axis(v: f64) -> f64 {
    (2.0 * v - 1.0).clamp(-1.0, 1.0).powi(3)
}

/// Fractional texel coordinates of (h, mu, mu_s): node-centred, the first and last texels on
/// the ends of each axis; altitude as √(h/H).
pub fn texel_from_h_mu_mu_s(p: &Params, h: f64, mu: f64, mu_s: f64) -> [f64; 3] {
    [
        cosine_axis(mu) * f64::from(MU - 1),
        cosine_axis(mu_s) * f64::from(MU_S - 1),
        (h / p.thickness_m()).clamp(0.0, 1.0).sqrt() * f64::from(H - 1),
    ]
}

/// The inverse of [`texel_from_h_mu_mu_s`]: (h, mu, mu_s).
pub fn h_mu_mu_s_from_texel(p: &Params, [x, y, z]: [f64; 3]) -> (f64, f64, f64) {
    let u = z / f64::from(H - 1);
    (
        u * u * p.thickness_m(),
        cosine_from_axis(x / f64::from(MU - 1)),
        cosine_from_axis(y / f64::from(MU_S - 1)),
    )
}

/// The texel's ray in the canonical frame, the sun in the view's half-plane (azimuth 0).
pub fn coords(p: &Params, x: usize, y: usize, z: usize) -> Coords {
    let (h, mu, mu_s) = h_mu_mu_s_from_texel(p, [x as f64, y as f64, z as f64]);
    let spread = ((1.0 - mu * mu) * (1.0 - mu_s * mu_s)).max(0.0).sqrt();
    Coords {
        h,
        mu,
        mu_s,
        nu: (mu * mu_s + spread).clamp(-1.0, 1.0),
        ground: hits_ground(h, mu, p.bottom_radius_m),
    }
}

/// Looks up a scattering table at (h, mu, mu_s), trilinearly.
pub fn look_up(p: &Params, lut: &Lut, layer: usize, h: f64, mu: f64, mu_s: f64) -> Lanes {
    let [fx, fy, fz] = texel_from_h_mu_mu_s(p, h, mu, mu_s);
    lut.trilinear(layer, fx, fy, fz)
}

/// The notes' modified Rayleigh phase function at view–sun cosine `nu`, sr⁻¹:
/// 0.8·(1.4 + 0.5·nu)/(4π). Linear in nu so that the sky opposite the sun is darkest; not
/// normalised (its mean over the sphere is 1.12/(4π)).
pub fn modified_rayleigh_phase(nu: f64) -> f64 {
    let [a, b] = crate::phase::ELEK_MODIFIED_RAYLEIGH;
    (a + b * nu) / (4.0 * std::f64::consts::PI)
}

/// Every table of the method for one atmosphere and viewpoint, in the state the GPU leaves them.
#[derive(Debug, Clone)]
pub struct Tables {
    pub params: Params,
    pub transmittance: Lut,
    pub delta_rayleigh: Lut,
    pub delta_mie: Lut,
    pub rayleigh: Lut,
    pub mie: Lut,
    pub gathered_rayleigh: Lut,
    pub gathered_mie: Lut,
    /// The Rayleigh and Mie tables' rows at the viewpoint ([`camera_slice`]).
    pub camera_rayleigh: Lut,
    pub camera_mie: Lut,
}

impl Tables {
    /// The transmittance and single scattering, then orders 2..=`p.scattering_orders`, each
    /// gathered from the one before; and both tables' rows at viewpoint `vp`.
    pub fn compute(p: &Params, vp: Viewpoint) -> Tables {
        let layers = p.batches.len();
        let t = compute_transmittance_lut(p);
        let (mut delta_rayleigh, mut delta_mie) =
            Lut::pair_from_spec(&DELTA_RAYLEIGH, layers, |layer, z, y, x| {
                single_scattering::single_scattering(p, &t, layer, coords(p, x, y, z))
            });
        let (mut rayleigh, mut mie) = (delta_rayleigh.clone(), delta_mie.clone());
        let zeros = Lut::from_spec(&GATHERED_RAYLEIGH, layers, |_, _, _, _| Lanes::ZERO);
        let (mut gathered_rayleigh, mut gathered_mie) = (zeros.clone(), zeros);
        for _order in 2..=p.scattering_orders {
            (gathered_rayleigh, gathered_mie) =
                Lut::pair_from_spec(&GATHERED_RAYLEIGH, layers, |layer, z, y, x| {
                    let (h, mu, mu_s) = h_mu_mu_s_from_texel(p, [x as f64, y as f64, z as f64]);
                    gather::gather(p, (&delta_rayleigh, &delta_mie), layer, h, mu, mu_s)
                });
            (delta_rayleigh, delta_mie) =
                Lut::pair_from_spec(&DELTA_RAYLEIGH, layers, |layer, z, y, x| {
                    multiple_scattering::multiple_scattering(
                        p,
                        &t,
                        (&gathered_rayleigh, &gathered_mie),
                        layer,
                        coords(p, x, y, z),
                    )
                });
            rayleigh = accumulate::accumulate(&rayleigh, &delta_rayleigh);
            mie = accumulate::accumulate(&mie, &delta_mie);
        }
        let (camera_rayleigh, camera_mie) = camera_slices(p, (&rayleigh, &mie), vp);
        Tables {
            params: p.clone(),
            transmittance: t,
            delta_rayleigh,
            delta_mie,
            rayleigh,
            mie,
            gathered_rayleigh,
            gathered_mie,
            camera_rayleigh,
            camera_mie,
        }
    }
}

/// The Rayleigh and Mie tables' rows at viewpoint `vp`.
fn camera_slices(p: &Params, (rayleigh, mie): (&Lut, &Lut), vp: Viewpoint) -> (Lut, Lut) {
    let slice = |spec, lut| camera_slice::compute_camera_slice(p, spec, lut, vp);
    (
        slice(&camera_slice::CAMERA_RAYLEIGH, rayleigh),
        slice(&camera_slice::CAMERA_MIE, mie),
    )
}

impl SkyModel for Tables {
    fn params(&self) -> &Params {
        &self.params
    }

    fn radiance(&self, layer: usize, at: (DVec3, f64), dir: DVec3, sun: DVec3) -> Lanes {
        sky::radiance(self, layer, at, dir, sun)
    }

    fn table(&self, id: &str) -> Option<&Lut> {
        Some(match id {
            "transmittance" => &self.transmittance,
            "delta-rayleigh" => &self.delta_rayleigh,
            "delta-mie" => &self.delta_mie,
            "rayleigh-scattering" => &self.rayleigh,
            "mie-scattering" => &self.mie,
            "gathered-rayleigh" => &self.gathered_rayleigh,
            "gathered-mie" => &self.gathered_mie,
            "camera-rayleigh" => &self.camera_rayleigh,
            "camera-mie" => &self.camera_mie,
            _ => return None,
        })
    }

    fn move_to(&mut self, vp: Viewpoint) -> bool {
        (self.camera_rayleigh, self.camera_mie) =
            camera_slices(&self.params, (&self.rayleigh, &self.mie), vp);
        true
    }
}

/// Builds the method's CPU twin (the registry's constructor).
pub fn build(params: &Params, vp: Viewpoint) -> Box<dyn SkyModel> {
    Box::new(Tables::compute(params, vp))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::direction_from_angles;
    use crate::methods::shared::optics::tests::params;

    /// The viewpoint of the tables at the camera where a test reads only the 3D tables.
    pub(super) const GROUND_NOON: Viewpoint = Viewpoint { h: 0.0, mu_s: 1.0 };

    #[test]
    fn the_mapping_round_trips_and_puts_nodes_on_the_ends() {
        let p = params();
        for (h, mu, mu_s) in [
            (0.0, 0.5, 0.3),
            (1500.0, -0.3, 0.8),
            (20_000.0, 0.02, -0.1),
            (60_000.0, -0.999, 0.95),
            (p.thickness_m(), 1.0, -1.0),
        ] {
            let f = texel_from_h_mu_mu_s(&p, h, mu, mu_s);
            let (h2, mu2, mu_s2) = h_mu_mu_s_from_texel(&p, f);
            assert!((h2 - h).abs() < 1e-6 * (1.0 + h), "h {h} -> {h2}");
            assert!((mu2 - mu).abs() < 1e-12 && (mu_s2 - mu_s).abs() < 1e-12);
        }
        assert_eq!(texel_from_h_mu_mu_s(&p, 0.0, -1.0, -1.0), [0.0, 0.0, 0.0]);
        assert_eq!(
            texel_from_h_mu_mu_s(&p, p.thickness_m(), 1.0, 1.0),
            [f64::from(MU - 1), f64::from(MU_S - 1), f64::from(H - 1)]
        );
        // The cube root puts half the texels within 7.2° of the horizontal (|c| < 0.5³).
        assert!((cosine_from_axis(0.75) - 0.125).abs() < 1e-15);
        // The canonical frame puts the sun in the view's half-plane.
        let c = coords(&p, 100, 20, 5);
        let view = crate::methods::shared::local_sun(c.mu);
        let sun = crate::methods::shared::local_sun(c.mu_s);
        assert!((view.dot(sun) - c.nu).abs() < 1e-12);
    }

    #[test]
    fn the_modified_rayleigh_phase_is_the_notes_line() {
        let four_pi = 4.0 * std::f64::consts::PI;
        assert!((modified_rayleigh_phase(1.0) * four_pi - 1.52).abs() < 1e-12);
        assert!((modified_rayleigh_phase(-1.0) * four_pi - 0.72).abs() < 1e-12);
        // Its mean over the sphere is 1.12/(4π): linear in nu, so the mean is the value at 0.
        assert!((modified_rayleigh_phase(0.0) * four_pi - 1.12).abs() < 1e-12);
    }

    #[test]
    fn each_order_adds_light_and_the_orders_shrink() {
        let mut p = params();
        p.steps.sphere_directions = 6;
        let radiance = |orders: u32| {
            let t = Tables::compute(&p.clone().with_scattering_orders(orders), GROUND_NOON);
            let position = DVec3::new(0.0, 0.0, p.bottom_radius_m + 100.0);
            let dir = direction_from_angles(40.0, 90.0);
            let sun = direction_from_angles(20.0, 0.0);
            (t.radiance(0, (position, 100.0), dir, sun)[0], t)
        };
        let (one, t1) = radiance(1);
        let (two, _) = radiance(2);
        let (three, t3) = radiance(3);
        assert!(one < two && two < three, "{one} {two} {three}");
        assert!(
            three - two < two - one,
            "orders shrink: {one} {two} {three}"
        );
        assert!(t1.gathered_rayleigh.data.iter().all(|v| v[0] == 0.0));
        assert!(t3.gathered_mie.data.iter().any(|v| v[0] > 0.0));
        assert!(
            t3.delta_mie.data.iter().any(|v| v[0] > 0.0),
            "Mie feeds Mie in every order"
        );
    }
}
