//! Polarised skylight: Stokes vectors in the local meridian frame, and the polarisation of
//! sunlight scattered once by air (Chandrasekhar 1950, §I.15–17; Hansen & Travis 1974, §2.2).
//!
//! **The frame.** At the observer, looking along `view` (into the sky), the reference
//! direction `e_up` lies in the meridian plane (the plane through the local zenith and the
//! view), perpendicular to the view and towards the zenith: "up" in an upright picture.
//! `e_right = view × e_up` is "right". The angle of polarisation χ is the angle of the electric
//! vector from `e_up` towards `e_right` (clockwise as the observer sees the sky), in −90°–90°,
//! and Q = I·P·cos 2χ, U = I·P·sin 2χ: Q > 0 where the light vibrates vertically (in the
//! meridian plane), Q < 0 horizontally: Chandrasekhar's Q, with U of the sign opposite to the
//! IAU's (which counts the angle counter-clockwise as seen on the sky). Straight up or down the
//! meridian plane is undefined: `e_up` is then the scene frame's north (+y; the camera's north
//! unless it has moved back over the planet).
//!
//! **Once-scattered sunlight.** Air scatters unpolarised sunlight into light polarised
//! perpendicular to the scattering plane (the plane of the sun, the scatterer and the
//! observer), by the degree [`rayleigh_degree`]. A Mie aerosol polarises by its own matrix
//! (across the plane or, at some angles, along it); the aerosols of the Henyey–Greenstein and
//! Cornette–Shanks phases scatter without polarising, and the Lambertian ground depolarises:
//! they add to I alone. The scattering angle is the same all along a view ray (the sun is at
//! infinity), so the polarised radiance of single scattering is each constituent's degree at
//! that angle times its part of the single-scattered radiance.
//!
//! The exact single scattering's Stokes vectors are `methods::single_scattering::stokes`; many
//! orders are the vector path tracer's (`methods::path_tracer`), with the matrices and
//! rotations of [`mueller`]; the real-time models' polarisation is
//! `methods::shared::polarisation`.

pub mod estimate;
pub mod mueller;
pub mod neutral_points;

use glam::DVec3;

/// A Stokes vector (I, Q, U, V) in the meridian frame, in the unit of the radiance.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Stokes {
    pub i: f64,
    pub q: f64,
    pub u: f64,
    pub v: f64,
}

impl Stokes {
    /// Light of radiance `i` polarised by degree `degree` (0–1) at angle `chi` (radians) from
    /// the frame's `e_up` (a negative degree: at χ + 90°).
    pub fn polarised(i: f64, degree: f64, chi: f64) -> Stokes {
        // Rounding leaves U a few parts in 10¹⁶ of I where χ is ±90°: zero, so that the angle
        // comes out +90° rather than either sign.
        let u = i * degree * (2.0 * chi).sin();
        Stokes {
            i,
            q: i * degree * (2.0 * chi).cos(),
            u: if u.abs() < 1e-12 * i.abs() { 0.0 } else { u },
            v: 0.0,
        }
    }

    /// The sum of two Stokes vectors (in the same frame): incoherent light adds.
    pub fn plus(self, o: Stokes) -> Stokes {
        Stokes {
            i: self.i + o.i,
            q: self.q + o.q,
            u: self.u + o.u,
            v: self.v + o.v,
        }
    }

    pub fn scaled(self, k: f64) -> Stokes {
        Stokes {
            i: k * self.i,
            q: k * self.q,
            u: k * self.u,
            v: k * self.v,
        }
    }

    pub fn to_array(self) -> [f64; 4] {
        [self.i, self.q, self.u, self.v]
    }

    /// The degree of polarisation √(Q² + U² + V²)/I, 0–1 (0 where I is 0).
    pub fn degree_of_polarization(&self) -> f64 {
        if self.i > 0.0 {
            ((self.q * self.q + self.u * self.u + self.v * self.v).sqrt() / self.i).min(1.0)
        } else {
            0.0
        }
    }

    /// The angle of polarisation χ = ½·atan2(U, Q), degrees in (−90, 90] (the frame's docs).
    pub fn angle_of_polarization_deg(&self) -> f64 {
        // + 0.0 turns −0 into 0.
        0.5 * self.u.atan2(self.q).to_degrees() + 0.0
    }
}

/// The degree of linear polarisation of unpolarised light scattered once by air at scattering
/// cosine `nu`, for depolarisation ratio `rho` (0 = ideal dipoles; air ≈ 0.03):
/// (1−γ)·sin²Θ / [(1+3γ) + (1−γ)·cos²Θ] with γ = ρ/(2−ρ), the ratio of the phase matrix's
/// polarising term to `phase::rayleigh`'s. At 90° it is (1−ρ)/(1+ρ); without depolarisation,
/// sin²Θ/(1+cos²Θ).
pub fn rayleigh_degree(nu: f64, rho: f64) -> f64 {
    let gamma = rho / (2.0 - rho);
    let nu2 = (nu * nu).min(1.0);
    (1.0 - gamma) * (1.0 - nu2) / ((1.0 + 3.0 * gamma) + (1.0 - gamma) * nu2)
}

/// The meridian frame (`e_up`, `e_right`) of a view direction `view` at a point whose local
/// zenith is `zenith` (unit vectors).
pub fn meridian_frame(view: DVec3, zenith: DVec3) -> (DVec3, DVec3) {
    let across = |d: DVec3| d - view * view.dot(d);
    // Straight up or down: north (the frame's +y), or east where the view lies along +y.
    let up = [zenith, DVec3::Y, DVec3::X]
        .into_iter()
        .map(across)
        .find(|u| u.length_squared() > 1e-18)
        .unwrap_or(DVec3::Z)
        .normalize();
    (up, view.cross(up))
}

/// The angle (radians) from the frame's `e_up` to the electric vector of light scattered
/// towards the observer from `view` out of sunlight from the sun in direction `sun`: the
/// vector perpendicular to the scattering plane.
pub fn perpendicular_angle(view: DVec3, sun: DVec3, zenith: DVec3) -> f64 {
    let (up, right) = meridian_frame(view, zenith);
    let e = view.cross(sun);
    let chi = e.dot(right).atan2(e.dot(up));
    // An electric vector and its opposite are the same polarisation: fold into −90°–90°.
    if chi > std::f64::consts::FRAC_PI_2 {
        chi - std::f64::consts::PI
    } else if chi < -std::f64::consts::FRAC_PI_2 {
        chi + std::f64::consts::PI
    } else {
        chi
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::direction_from_angles;

    #[test]
    fn rayleighs_degree_is_the_classic_formula() {
        for deg in [0.0f64, 30.0, 60.0, 90.0, 120.0, 180.0] {
            let nu = deg.to_radians().cos();
            let ideal = (1.0 - nu * nu) / (1.0 + nu * nu);
            assert!((rayleigh_degree(nu, 0.0) - ideal).abs() < 1e-12, "{deg}");
        }
        // With depolarisation, at 90°: (1−ρ)/(1+ρ).
        let rho = 0.0279;
        assert!((rayleigh_degree(0.0, rho) - (1.0 - rho) / (1.0 + rho)).abs() < 1e-12);
        // The scaled form sin²Θ/(1 + cos²Θ + 2ρ/(1−ρ)).
        let nu: f64 = 0.4;
        let scaled = (1.0 - nu * nu) / (1.0 + nu * nu + 2.0 * rho / (1.0 - rho));
        assert!((rayleigh_degree(nu, rho) - scaled).abs() < 1e-12);
    }

    /// The handedness of the frame: with the sun 45° up in the east and the view 45° up in
    /// the north, the sun appears up and to the right of the view's centre, and the electric
    /// vector across the scattering plane lies at −atan(1/√2) from up (clockwise positive);
    /// with the sun in the west, at +atan(1/√2).
    #[test]
    fn the_angle_runs_clockwise_from_up_as_the_observer_sees_the_sky() {
        let view = direction_from_angles(45.0, 0.0);
        let expected = (1.0f64 / 2.0f64.sqrt()).atan();
        for (sun_azimuth, sign) in [(90.0, -1.0), (270.0, 1.0)] {
            let chi = perpendicular_angle(view, direction_from_angles(45.0, sun_azimuth), DVec3::Z);
            assert!(
                (chi - sign * expected).abs() < 1e-12,
                "{sun_azimuth}: {chi}"
            );
        }
        // Straight up, up is north: the sun in the east gives a north–south vector.
        let chi = perpendicular_angle(DVec3::Z, direction_from_angles(0.0, 90.0), DVec3::Z);
        assert!(chi.abs() < 1e-12, "{chi}");
        let (up, right) = meridian_frame(DVec3::Y, DVec3::Z);
        assert_eq!((up, right), (DVec3::Z, DVec3::X));
    }
}
