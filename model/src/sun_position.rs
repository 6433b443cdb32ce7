//! Sun position from date, time and place: the NOAA solar calculator's equations, which are
//! Meeus' (1998, ch. 25) low-accuracy solar coordinates plus the equation of time. Accurate to
//! about 0.01° for 1900–2100. The elevation is geometric (no refraction): the renderer traces
//! straight rays, so a refracted sun would disagree with its own atmosphere.

use serde::{Deserialize, Serialize};

/// A civil date and time with its offset from UTC.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DateTime {
    /// Year, 1900–2100.
    pub year: i32,
    /// Month 1–12.
    pub month: u32,
    /// Day of month 1–31.
    pub day: u32,
    /// Local clock time in decimal hours, 0 ≤ hour < 24.
    pub hour: f64,
    /// Offset of the local clock from UTC, hours (−12 to +14), e.g. −7 for MST.
    pub utc_offset_h: f64,
}

impl DateTime {
    /// Julian day (UT) of this instant (Meeus ch. 7, Gregorian calendar).
    pub fn julian_day(&self) -> f64 {
        let (mut y, mut m) = (self.year as f64, self.month as f64);
        if m <= 2.0 {
            y -= 1.0;
            m += 12.0;
        }
        let a = (y / 100.0).floor();
        let b = 2.0 - a + (a / 4.0).floor();
        let day = self.day as f64 + (self.hour - self.utc_offset_h) / 24.0;
        (365.25 * (y + 4716.0)).floor() + (30.6001 * (m + 1.0)).floor() + day + b - 1524.5
    }
}

/// Apparent right ascension and declination of the sun, degrees, at Julian day `jd`.
pub fn equatorial_deg(jd: f64) -> (f64, f64) {
    let s = solar_terms(jd);
    let (eps, lambda) = (
        s.obliquity_deg.to_radians(),
        s.apparent_longitude_deg.to_radians(),
    );
    let ra = (eps.cos() * lambda.sin())
        .atan2(lambda.cos())
        .to_degrees()
        .rem_euclid(360.0);
    let dec = (eps.sin() * lambda.sin()).asin().to_degrees();
    (ra, dec)
}

struct SolarTerms {
    mean_longitude_deg: f64,
    mean_anomaly_deg: f64,
    eccentricity: f64,
    /// The equation of the centre C: true anomaly ν = M + C.
    equation_of_centre_deg: f64,
    apparent_longitude_deg: f64,
    obliquity_deg: f64,
}

fn solar_terms(jd: f64) -> SolarTerms {
    let t = (jd - 2_451_545.0) / 36_525.0;
    let l0 = (280.46646 + t * (36_000.76983 + t * 0.0003032)).rem_euclid(360.0);
    let m = 357.52911 + t * (35_999.05029 - t * 0.0001537);
    let e = 0.016708634 - t * (0.000042037 + t * 0.0000001267);
    let mr = m.to_radians();
    let c_deg = mr.sin() * (1.914602 - t * (0.004817 + t * 0.000014))
        + (2.0 * mr).sin() * (0.019993 - t * 0.000101)
        + (3.0 * mr).sin() * 0.000289;
    let omega = (125.04 - 1934.136 * t).to_radians();
    let apparent = l0 + c_deg - 0.00569 - 0.00478 * omega.sin();
    let eps0 =
        23.0 + (26.0 + (21.448 - t * (46.8150 + t * (0.00059 - t * 0.001813))) / 60.0) / 60.0;
    SolarTerms {
        mean_longitude_deg: l0,
        mean_anomaly_deg: m,
        eccentricity: e,
        equation_of_centre_deg: c_deg,
        apparent_longitude_deg: apparent,
        obliquity_deg: eps0 + 0.00256 * omega.cos(),
    }
}

/// The Earth–Sun distance at Julian day `jd`, astronomical units (Meeus 1998, eq. 25.5): 0.983
/// in early January to 1.017 in early July, so sunlight is 3.4 % stronger than at the mean
/// distance in January and 3.3 % weaker in July.
pub fn distance_au(jd: f64) -> f64 {
    let s = solar_terms(jd);
    let nu = (s.mean_anomaly_deg + s.equation_of_centre_deg).to_radians();
    let e = s.eccentricity;
    1.000001018 * (1.0 - e * e) / (1.0 + e * nu.cos())
}

/// Where the sun stands for an observer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunAngles {
    /// Geometric elevation above the horizon, degrees (−90 to 90).
    pub elevation_deg: f64,
    /// Azimuth clockwise from north, degrees [0, 360).
    pub azimuth_deg: f64,
}

/// Sun elevation and azimuth at `time` for latitude `latitude_deg` (north positive, −90 to 90)
/// and longitude `longitude_deg` (east positive, −180 to 180).
pub fn position(time: &DateTime, latitude_deg: f64, longitude_deg: f64) -> SunAngles {
    let jd = time.julian_day();
    let s = solar_terms(jd);
    let (_, dec) = equatorial_deg(jd);
    let y = (s.obliquity_deg.to_radians() / 2.0).tan().powi(2);
    let (l0, m, e) = (
        s.mean_longitude_deg.to_radians(),
        s.mean_anomaly_deg.to_radians(),
        s.eccentricity,
    );
    let eot_min = 4.0
        * (y * (2.0 * l0).sin() - 2.0 * e * m.sin() + 4.0 * e * y * m.sin() * (2.0 * l0).cos()
            - 0.5 * y * y * (4.0 * l0).sin()
            - 1.25 * e * e * (2.0 * m).sin())
        .to_degrees();
    let utc_minutes = (time.hour - time.utc_offset_h) * 60.0;
    let true_solar_min = (utc_minutes + eot_min + 4.0 * longitude_deg).rem_euclid(1440.0);
    let hour_angle = (true_solar_min / 4.0 - 180.0).to_radians();
    let (phi, delta) = (latitude_deg.to_radians(), dec.to_radians());
    let cos_zenith =
        (phi.sin() * delta.sin() + phi.cos() * delta.cos() * hour_angle.cos()).clamp(-1.0, 1.0);
    let azimuth = hour_angle
        .sin()
        .atan2(hour_angle.cos() * phi.sin() - delta.tan() * phi.cos())
        .to_degrees()
        + 180.0;
    SunAngles {
        elevation_deg: 90.0 - cos_zenith.acos().to_degrees(),
        azimuth_deg: azimuth.rem_euclid(360.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn meeus_example_25a() {
        // Meeus, Astronomical Algorithms (1998), example 25.a: 1992 October 13.0 TD,
        // α = 13h13m31.4s = 198.38083°, δ = −7°47′06″ = −7.78507°.
        let t = DateTime {
            year: 1992,
            month: 10,
            day: 13,
            hour: 0.0,
            utc_offset_h: 0.0,
        };
        assert_eq!(t.julian_day(), 2_448_908.5);
        let (ra, dec) = equatorial_deg(t.julian_day());
        assert!((ra - 198.38083).abs() < 0.001, "α = {ra}");
        assert!((dec + 7.78507).abs() < 0.001, "δ = {dec}");
        // Same example: R = 0.99766 AU.
        let r = distance_au(t.julian_day());
        assert!((r - 0.99766).abs() < 2e-5, "R = {r}");
    }

    #[test]
    fn the_earth_is_nearest_the_sun_in_january_and_farthest_in_july() {
        let on = |month, day| {
            distance_au(
                DateTime {
                    year: 2026,
                    month,
                    day,
                    hour: 12.0,
                    utc_offset_h: 0.0,
                }
                .julian_day(),
            )
        };
        let (perihelion, aphelion) = (on(1, 3), on(7, 6));
        assert!((perihelion - 0.9833).abs() < 5e-4, "{perihelion}");
        assert!((aphelion - 1.0167).abs() < 5e-4, "{aphelion}");
    }

    #[test]
    fn nrel_spa_example() {
        // Reda & Andreas (2004), NREL SPA example: 2003-10-17 12:30:30 MST (UTC−7), 39.742476° N,
        // 105.1786° W, 820 hPa, 11 °C. Published: topocentric azimuth 194.34024°, zenith
        // 50.11162° including refraction. Adding back SPA's own refraction term gives the
        // geometric zenith this module computes.
        let t = DateTime {
            year: 2003,
            month: 10,
            day: 17,
            hour: 12.0 + 30.5 / 60.0,
            utc_offset_h: -7.0,
        };
        let s = position(&t, 39.742476, -105.1786);
        assert!(
            (s.azimuth_deg - 194.34024).abs() < 0.01,
            "azimuth {}",
            s.azimuth_deg
        );
        let e0 = 90.0 - 50.11162_f64;
        let refraction = (820.0 / 1010.0) * (283.0 / (273.0 + 11.0)) * 1.02
            / (60.0 * (e0 + 10.3 / (e0 + 5.11)).to_radians().tan());
        let zenith = 90.0 - s.elevation_deg;
        assert!(
            (zenith - (50.11162 + refraction)).abs() < 0.01,
            "zenith {zenith}"
        );
    }

    #[test]
    fn equinox_solar_noon_at_the_equator_is_overhead_and_late_by_the_equation_of_time() {
        // On 2024-03-20 the equation of time is about −7.5 min: the sun culminates at 0° E near
        // 12:07.5 UTC, within 0.5° of the zenith (declination ≈ 0°).
        let at = |minute: u32| {
            let t = DateTime {
                year: 2024,
                month: 3,
                day: 20,
                hour: 11.0 + minute as f64 / 60.0,
                utc_offset_h: 0.0,
            };
            position(&t, 0.0, 0.0).elevation_deg
        };
        let noon = (0..120).max_by(|&a, &b| at(a).total_cmp(&at(b))).unwrap();
        assert!(
            (65..=70).contains(&noon),
            "culmination at 11:00 + {noon} min"
        );
        assert!(at(noon) > 89.5, "{}", at(noon));
    }
}
