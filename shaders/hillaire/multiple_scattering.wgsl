// Pass: multiple-scattering table Ψ_ms(h, mu_s) = L_2nd / (1 − f_ms), per unit solar irradiance
// (Hillaire 2020 §5.5), with an isotropic phase and the sunlit ground bounce, over the directions
// on one side of the sun's vertical plane (their mirror images see the same). One workgroup per
// texel, its invocations sharing the directions, as Hillaire's own pass does.

fn sphere_direction(i: u32, n: u32) -> vec3<f32> {
    let mu = 1.0 - 2.0 * (f32(i / n) + 0.5) / f32(n);
    let phi = 2.0 * PI * (f32(i % n) + 0.5) / f32(n);
    let s = sqrt(max(1.0 - mu * mu, 0.0));
    return vec3<f32>(s * cos(phi), s * sin(phi), mu);
}

@compute @workgroup_size(TEXEL_GROUP_SIZE, 1, 1)
fn main(
    @builtin(workgroup_id) workgroup: vec3<u32>,
    @builtin(local_invocation_index) index: u32,
) {
    let id = dispatched_texel(workgroup);
    if any(id.xy >= MULTIPLE_SCATTERING_SIZE) || id.z >= batch_count() {
        return;
    }
    let layer = id.z;
    let hm = multiple_scattering_h_mu_s_from_texel(vec2<f32>(id.xy));
    let h = hm.x;
    let mu_s = hm.y;
    let r = bottom_radius() + h;
    let sun = local_sun(mu_s);
    let isotropic = 1.0 / (4.0 * PI);
    let b = batches[layer];
    let albedo = b.ground_albedo;
    let n_dir = MULTIPLE_SCATTERING_DIRECTIONS_SQRT;
    let n = globals.steps_a.y;
    var l_2nd = vec4<f32>(0.0);
    var f_ms = vec4<f32>(0.0);
    // One side of the sun's vertical plane: a mirror direction has the same mu and nu.
    let half = n_dir / 2u;
    for (var d = index; d < n_dir * half; d += TEXEL_GROUP_SIZE) {
        let omega = sphere_direction((d / half) * n_dir + d % half, n_dir);
        let mu = omega.z;
        let nu = dot(omega, sun);
        let ground = hits_ground(h, mu);
        var t_max: f32;
        if ground {
            t_max = distance_to_ground(h, mu);
        } else {
            t_max = distance_to_top(h, mu);
        }
        var throughput = vec4<f32>(1.0);
        for (var s = 0u; s < n; s++) {
            let seg = march_segment(SPACING_QUADRATIC, 0.0, t_max, s, n);
            let ts = 0.5 * (seg.x + seg.y);
            let dt = seg.y - seg.x;
            let at = altitude_along(h, mu, ts);
            let mu_s_t = (r * mu_s + ts * nu) / at.y;
            let m = medium(b, at.x);
            let weight = throughput * segment_weight(m.extinction, dt);
            let sca = m.rayleigh_scattering + m.aerosol_scattering;
            let sun_t = sun_transmittance(layer, at.x, mu_s_t);
            l_2nd += weight * sca * isotropic * sun_t;
            f_ms += weight * sca;
            throughput *= exp(-m.extinction * dt);
        }
        if ground {
            let mu_s_g = (r * mu_s + t_max * nu) / bottom_radius();
            let sun_t = sun_transmittance(layer, 0.0, mu_s_g);
            l_2nd += throughput * sun_t * max(mu_s_g, 0.0) * albedo / PI;
        }
    }
    let sums = group_sums(index, l_2nd, f_ms);
    if index == 0u {
        let count = f32(n_dir * half);
        let psi = (sums[0] / count) / (1.0 - sums[1] / count);
        let size = MULTIPLE_SCATTERING_SIZE;
        multiple_scattering_lut[(layer * size.y + id.y) * size.x + id.x] = psi;
    }
}
