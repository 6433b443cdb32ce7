// Pass: the view with Bruneton (2017): the scattering tables times their phase functions and
// the ground lit by the sun and the sky irradiance; from above the atmosphere the look-up
// starts where the ray enters it (common/ray.wgsl), and a ray that starts with the sun beyond
// the tables' 102° from where it comes back to 102°. Twin of model::methods::bruneton::sky.

// 1 with the sun within the tables' range, falling to 0 over BRUNETON_MU_S_FADE below it.
fn edge_fade(mu_s: f32) -> f32 {
    return clamp((mu_s - (BRUNETON_MU_S_MIN - BRUNETON_MU_S_FADE)) / BRUNETON_MU_S_FADE, 0.0, 1.0);
}

fn ground_radiance(layer: u32, mu_s_g: f32) -> vec4<f32> {
    let b = batches[layer];
    return b.ground_albedo / PI * (b.solar_irradiance * sun_transmittance(layer, 0.0, mu_s_g) * max(mu_s_g, 0.0)
        + edge_fade(mu_s_g) * read_irradiance(layer, 0.0, mu_s_g));
}

// The distance along the ray of c at which the sun's zenith cosine first rises to the tables'
// edge, BRUNETON_MU_S_MIN, or -1 if it does not before the ray ends (twin of
// bruneton::sky::lit_distance: the smallest positive root of mu_s(d)^2 = m^2).
fn lit_distance(c: Coords) -> f32 {
    let r = bottom_radius() + c.h;
    let m2 = BRUNETON_MU_S_MIN * BRUNETON_MU_S_MIN;
    let a = c.nu * c.nu - m2;
    let half_b = r * (c.mu_s * c.nu - m2 * c.mu);
    let cc = r * r * (c.mu_s * c.mu_s - m2);
    let disc = half_b * half_b - a * cc;
    if disc < 0.0 {
        return -1.0;
    }
    let q = -(half_b + select(-1.0, 1.0, half_b >= 0.0) * sqrt(disc));
    var d = 3.0e38;
    if a != 0.0 && q / a > 0.0 {
        d = q / a;
    }
    if q != 0.0 && cc / q > 0.0 {
        d = min(d, cc / q);
    }
    return select(-1.0, d, d <= ray_length(c));
}

// Whether a ray of the view may start with the sun below the tables (from above the atmosphere,
// or with the sun that low at the camera); the engine sets it per frame. When not, every ray
// starts at the camera, and the look-up reads the tables' slices there.
override SUN_BELOW_TABLES: bool = true;

// The tables' in-scattered radiance along the ray of c; beyond their range, read where the sun
// comes back to 102° along the ray, or at the edge faded to dark. One look-up either way (a
// software GPU runs both sides of a branch). Twin of bruneton::sky::inscattered.
fn inscattered(layer: u32, c: Coords) -> vec4<f32> {
    let b = batches[layer];
    var at = c;
    var factor = vec4<f32>(1.0);
    if SUN_BELOW_TABLES && c.mu_s < BRUNETON_MU_S_MIN {
        let d = lit_distance(c);
        if d >= 0.0 {
            let p = along(c, d);
            at.h = p.x;
            at.mu = p.y;
            at.mu_s = p.z;
            factor = transmittance_between(layer, c.h, c.mu, d);
        } else {
            factor = vec4<f32>(edge_fade(c.mu_s));
        }
    }
    var s: Inscattered;
    if SUN_BELOW_TABLES {
        s = read_scattering(scattering_cell(layer, scattering_texel(at)));
    } else {
        s = read_camera_slice(layer, c);
    }
    return factor * (s.scattering * rayleigh_phase(c.nu, b.rayleigh_depolarisation)
        + s.single_mie * aerosol_phase(c.nu, layer));
}

// The tables at the camera (camera_slice.wgsl) for a ray that starts there: what the 4D
// look-up gives, from four texels of each. Twin of bruneton::camera_slice::camera_slice; the
// CPU sky reads the 4D tables, the same value.
fn read_camera_slice(layer: u32, c: Coords) -> Inscattered {
    let size = vec2<u32>(SCATTERING_NU, SCATTERING_SIZE.y);
    let t = taps(size, layer, vec2<f32>(nu_texel(c.nu), mu_texel(c.h, c.mu, c.ground)));
    return Inscattered(
        blend(camera_scattering_lut[t.i.x], camera_scattering_lut[t.i.y],
            camera_scattering_lut[t.i.z], camera_scattering_lut[t.i.w], t.w),
        blend(camera_single_mie_lut[t.i.x], camera_single_mie_lut[t.i.y],
            camera_single_mie_lut[t.i.z], camera_single_mie_lut[t.i.w], t.w));
}

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let camera = camera_coords(dir);
    if !camera.hit {
        return vec4<f32>(0.0);
    }
    let c = camera.c;
    let s = inscattered(layer, c);
    if c.ground {
        let g = ground_hit(layer, c);
        return s + g.transmittance * ground_radiance(layer, g.mu_s);
    }
    return s;
}
