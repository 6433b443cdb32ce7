//! Colour science: spectral radiance → CIE XYZ (1931 2° observer) → linear sRGB (D65),
//! luminance in cd/m², CIELAB, CIEDE2000 colour difference and the sRGB transfer function.
//!
//! Matrices follow IEC 61966-2-1 (sRGB); CIEDE2000 follows Sharma, Wu & Dalal (2005), whose
//! published test pairs pin it in the tests.

use crate::constants::{MAX_LUMINOUS_EFFICACY_LM_PER_W, VISIBLE_MAX_NM};
use crate::csv_table::tables;
use crate::spectrum::Spectrum;
use std::sync::OnceLock;

/// CIE 1931 2° colour-matching functions x̄, ȳ, z̄, 360–830 nm at 1 nm.
pub struct ColourMatching {
    pub x: Spectrum,
    pub y: Spectrum,
    pub z: Spectrum,
}

/// The CIE 1931 2° standard observer.
pub fn cie1931() -> &'static ColourMatching {
    static CMF: OnceLock<ColourMatching> = OnceLock::new();
    CMF.get_or_init(|| {
        let t = tables::cie1931_2deg();
        ColourMatching {
            x: Spectrum::from_table(t, "wavelength_nm", "x"),
            y: Spectrum::from_table(t, "wavelength_nm", "y"),
            z: Spectrum::from_table(t, "wavelength_nm", "z"),
        }
    })
}

/// Tristimulus values; for radiance input X, Y, Z are ∫ x̄L dλ etc. (W·m⁻²·sr⁻¹).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Xyz {
    pub x: f64,
    pub y: f64,
    pub z: f64,
}

/// Integrates a spectral radiance (W·m⁻²·sr⁻¹·nm⁻¹) against the CIE 1931 functions at 1 nm.
pub fn spectrum_to_xyz(radiance: &Spectrum) -> Xyz {
    let cmf = cie1931();
    let mut xyz = Xyz::default();
    for (i, &w) in cmf.y.wavelengths_nm().iter().enumerate() {
        // Trapezoid weights on the CMF's own 1 nm grid.
        let weight = if i == 0 || w >= VISIBLE_MAX_NM {
            0.5
        } else {
            1.0
        };
        let l = radiance.sample(w) * weight;
        xyz.x += l * cmf.x.values()[i];
        xyz.y += l * cmf.y.values()[i];
        xyz.z += l * cmf.z.values()[i];
    }
    xyz
}

/// Luminance in cd/m² of a spectral radiance in W·m⁻²·sr⁻¹·nm⁻¹: 683·∫ȳL dλ.
pub fn luminance_cd_m2(radiance: &Spectrum) -> f64 {
    MAX_LUMINOUS_EFFICACY_LM_PER_W * spectrum_to_xyz(radiance).y
}

/// Linear sRGB (D65 white) from XYZ, IEC 61966-2-1.
pub fn xyz_to_linear_srgb(c: Xyz) -> [f64; 3] {
    [
        3.2404542 * c.x - 1.5371385 * c.y - 0.4985314 * c.z,
        -0.9692660 * c.x + 1.8760108 * c.y + 0.0415560 * c.z,
        0.0556434 * c.x - 0.2040259 * c.y + 1.0572252 * c.z,
    ]
}

/// XYZ from linear sRGB (D65 white), IEC 61966-2-1.
pub fn linear_srgb_to_xyz(rgb: [f64; 3]) -> Xyz {
    Xyz {
        x: 0.4124564 * rgb[0] + 0.3575761 * rgb[1] + 0.1804375 * rgb[2],
        y: 0.2126729 * rgb[0] + 0.7151522 * rgb[1] + 0.0721750 * rgb[2],
        z: 0.0193339 * rgb[0] + 0.1191920 * rgb[1] + 0.9503041 * rgb[2],
    }
}

/// sRGB transfer function: linear [0, 1] → encoded [0, 1] (values outside are clamped).
pub fn srgb_encode(linear: f64) -> f64 {
    let c = linear.clamp(0.0, 1.0);
    if c <= 0.0031308 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}

/// Inverse sRGB transfer function: encoded [0, 1] → linear [0, 1].
pub fn srgb_decode(encoded: f64) -> f64 {
    let c = encoded.clamp(0.0, 1.0);
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// D65 reference white, Y = 1 (CIE 15:2004, 2° observer).
pub const D65_WHITE: Xyz = Xyz {
    x: 0.95047,
    y: 1.0,
    z: 1.08883,
};

/// CIELAB colour (L* in [0, 100]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lab {
    pub l: f64,
    pub a: f64,
    pub b: f64,
}

/// CIELAB of `c` relative to `white` (same scale as `c`).
pub fn xyz_to_lab(c: Xyz, white: Xyz) -> Lab {
    fn f(t: f64) -> f64 {
        const D: f64 = 6.0 / 29.0;
        if t > D * D * D {
            t.cbrt()
        } else {
            t / (3.0 * D * D) + 4.0 / 29.0
        }
    }
    let (fx, fy, fz) = (f(c.x / white.x), f(c.y / white.y), f(c.z / white.z));
    Lab {
        l: 116.0 * fy - 16.0,
        a: 500.0 * (fx - fy),
        b: 200.0 * (fy - fz),
    }
}

/// CIELAB of a display-referred linear sRGB colour (white = (1, 1, 1)).
pub fn linear_srgb_to_lab(rgb: [f64; 3]) -> Lab {
    xyz_to_lab(linear_srgb_to_xyz(rgb), D65_WHITE)
}

/// CIEDE2000 colour difference ΔE₀₀ with kL = kC = kH = 1 (Sharma, Wu & Dalal 2005).
pub fn delta_e2000(lab1: Lab, lab2: Lab) -> f64 {
    use std::f64::consts::PI;
    let deg = PI / 180.0;
    let c1 = lab1.a.hypot(lab1.b);
    let c2 = lab2.a.hypot(lab2.b);
    let c_mean = 0.5 * (c1 + c2);
    let c7 = c_mean.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + 25f64.powi(7))).sqrt());
    let a1 = (1.0 + g) * lab1.a;
    let a2 = (1.0 + g) * lab2.a;
    let c1p = a1.hypot(lab1.b);
    let c2p = a2.hypot(lab2.b);
    let hue = |b: f64, a: f64| {
        if a == 0.0 && b == 0.0 {
            0.0
        } else {
            let h = b.atan2(a) / deg;
            if h < 0.0 { h + 360.0 } else { h }
        }
    };
    let h1p = hue(lab1.b, a1);
    let h2p = hue(lab2.b, a2);
    let dl = lab2.l - lab1.l;
    let dc = c2p - c1p;
    let dh_angle = if c1p * c2p == 0.0 {
        0.0
    } else {
        let d = h2p - h1p;
        if d > 180.0 {
            d - 360.0
        } else if d < -180.0 {
            d + 360.0
        } else {
            d
        }
    };
    let dh = 2.0 * (c1p * c2p).sqrt() * (0.5 * dh_angle * deg).sin();
    let l_mean = 0.5 * (lab1.l + lab2.l);
    let cp_mean = 0.5 * (c1p + c2p);
    let h_mean = if c1p * c2p == 0.0 {
        h1p + h2p
    } else if (h1p - h2p).abs() <= 180.0 {
        0.5 * (h1p + h2p)
    } else if h1p + h2p < 360.0 {
        0.5 * (h1p + h2p + 360.0)
    } else {
        0.5 * (h1p + h2p - 360.0)
    };
    let t = 1.0 - 0.17 * ((h_mean - 30.0) * deg).cos()
        + 0.24 * ((2.0 * h_mean) * deg).cos()
        + 0.32 * ((3.0 * h_mean + 6.0) * deg).cos()
        - 0.20 * ((4.0 * h_mean - 63.0) * deg).cos();
    let d_theta = 30.0 * (-((h_mean - 275.0) / 25.0).powi(2)).exp();
    let cp7 = cp_mean.powi(7);
    let r_c = 2.0 * (cp7 / (cp7 + 25f64.powi(7))).sqrt();
    let l50 = (l_mean - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * cp_mean;
    let s_h = 1.0 + 0.015 * cp_mean * t;
    let r_t = -(2.0 * d_theta * deg).sin() * r_c;
    let (tl, tc, th) = (dl / s_l, dc / s_c, dh / s_h);
    (tl * tl + tc * tc + th * th + r_t * tc * th).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ybar_is_one_at_555_nm() {
        assert!((cie1931().y.sample(555.0) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn equal_energy_spectrum_has_equal_tristimulus_integrals() {
        // The CIE functions are normalised so that an equal-energy spectrum gives X ≈ Y ≈ Z.
        let flat = Spectrum::new(vec![300.0, 900.0], vec![1.0, 1.0]).unwrap();
        let c = spectrum_to_xyz(&flat);
        assert!((c.x / c.y - 1.0).abs() < 1e-3, "{c:?}");
        assert!((c.z / c.y - 1.0).abs() < 2e-3, "{c:?}");
        assert!((c.y - 106.857).abs() < 0.01, "∫ȳ = {}", c.y);
    }

    #[test]
    fn d65_maps_to_srgb_white() {
        let t = tables::cie_d65();
        let d65 = Spectrum::from_table(t, "wavelength_nm", "relative_power");
        let c = spectrum_to_xyz(&d65);
        let rgb = xyz_to_linear_srgb(Xyz {
            x: c.x / c.y,
            y: 1.0,
            z: c.z / c.y,
        });
        for v in rgb {
            assert!((v - 1.0).abs() < 0.01, "{rgb:?}");
        }
    }

    #[test]
    fn srgb_matrices_are_inverse() {
        let rgb = [0.2, 0.5, 0.9];
        let back = xyz_to_linear_srgb(linear_srgb_to_xyz(rgb));
        for i in 0..3 {
            assert!((back[i] - rgb[i]).abs() < 1e-6);
        }
    }

    #[test]
    fn srgb_transfer_round_trips() {
        for i in 0..=100 {
            let x = i as f64 / 100.0;
            assert!((srgb_decode(srgb_encode(x)) - x).abs() < 1e-12);
        }
        assert!((srgb_encode(0.5) - 0.735357).abs() < 1e-5);
    }

    #[test]
    fn ciede2000_matches_sharma_test_pairs() {
        // Pairs 1, 2, 3, 7 and 17 of Sharma, Wu & Dalal (2005), Table 1.
        let cases = [
            ((50.0, 2.6772, -79.7751), (50.0, 0.0, -82.7485), 2.0425),
            ((50.0, 3.1571, -77.2803), (50.0, 0.0, -82.7485), 2.8615),
            ((50.0, 2.8361, -74.0200), (50.0, 0.0, -82.7485), 3.4412),
            ((50.0, 0.0, 0.0), (50.0, -1.0, 2.0), 2.3669),
            ((50.0, 2.5, 0.0), (73.0, 25.0, -18.0), 27.1492),
        ];
        for (a, b, expected) in cases {
            let l1 = Lab {
                l: a.0,
                a: a.1,
                b: a.2,
            };
            let l2 = Lab {
                l: b.0,
                a: b.1,
                b: b.2,
            };
            let d = delta_e2000(l1, l2);
            assert!(
                (d - expected).abs() < 1e-4,
                "{a:?} {b:?}: {d} vs {expected}"
            );
            assert!((delta_e2000(l2, l1) - d).abs() < 1e-12, "symmetric");
        }
        let same = Lab {
            l: 40.0,
            a: 10.0,
            b: -5.0,
        };
        assert_eq!(delta_e2000(same, same), 0.0);
    }

    #[test]
    fn luminance_of_a_flat_spectrum() {
        let flat = Spectrum::new(vec![360.0, 830.0], vec![0.01, 0.01]).unwrap();
        let l = luminance_cd_m2(&flat);
        assert!((l - 683.0 * 0.01 * 106.857).abs() < 0.1, "{l}");
    }
}
