// Pass: the CIE standard general sky (CIE S 011 / ISO 15469): the type's indicatrix f(χ) times
// its gradation φ(Z), times each lane's radiance per unit of it (the zenith luminance over
// f(Z_s)·φ(0), spread as the solar spectrum), for the sky; the Lambertian ground's radiance
// for the ground (entry point: views/sky.wgsl). Twin of model::methods::cie_standard_sky::sky.
// The rows for the frame's sun arrive in batches[layer].model
// (model::methods::cie_standard_sky::batch_rows): 0 the scale per lane, 1 a, b, c, d, 2 e,
// 3 the sun's transmittance, 4 the ground's radiance.

const CIE_ROW_SUN: u32 = 3u;
const CIE_ROW_GROUND: u32 = 4u;

fn radiance(layer: u32, dir: vec3<f32>) -> vec4<f32> {
    let h = globals.camera_position.w;
    let up = normalize(globals.camera_position.xyz);
    let mu = dot(dir, up);
    let m = &batches[layer].model;
    if sees_ground(h, mu) {
        return (*m)[CIE_ROW_GROUND];
    }
    let k = (*m)[1];
    let e = (*m)[2].x;
    let chi = acos(clamp(dot(dir, globals.sun.xyz), -1.0, 1.0));
    var gradation = 1.0;
    if mu > 0.0 {
        gradation = 1.0 + k.x * exp(k.y / mu);
    }
    let cos_chi = cos(chi);
    let indicatrix = 1.0 + k.z * (exp(k.w * chi) - exp(k.w * 0.5 * PI)) + e * cos_chi * cos_chi;
    return (*m)[0] * max(gradation * indicatrix, 0.0);
}

// The sun's disk through Preetham's direct beam for the types that show it (else 0), where the
// planet does not hide it.
fn sun_through_atmosphere(layer: u32, h: f32, mu_s: f32) -> vec4<f32> {
    return batches[layer].model[CIE_ROW_SUN] * sun_visible_fraction(h, mu_s);
}
