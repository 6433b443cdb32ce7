// Pass: multiple-scattering table Ψ_ms(h, mu_s) = L_2nd / (1 − f_ms), per unit solar irradiance
// (Hillaire 2020 §5.5), with an isotropic phase and the sunlit ground bounce, over the directions
// on one side of the sun's vertical plane (their mirror images see the same). One workgroup per
// texel, its invocations sharing the directions, as Hillaire's own pass does; a workgroup of
// more invocations than directions (64 on a GPU, for 32) splits each direction's march into
// RUNS runs of steps, joined in order before the sums.

// The directions marched: one side of the sun's vertical plane.
const DIRECTIONS: u32 = MULTIPLE_SCATTERING_DIRECTIONS_SQRT * MULTIPLE_SCATTERING_DIRECTIONS_SQRT / 2u;
const RUNS: u32 = select(1u, TEXEL_GROUP_SIZE / DIRECTIONS, TEXEL_GROUP_SIZE >= 2u * DIRECTIONS);

// Each invocation's run's transmittance; its L_2nd and f_ms wait in group_a and group_b.
var<workgroup> run_transmittance: array<vec4<f32>, TEXEL_GROUP_SIZE>;

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
    let inside = all(id.xy < MULTIPLE_SCATTERING_SIZE) && id.z < batch_count();
    let layer = min(id.z, batch_count() - 1u);
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
    let part = index / DIRECTIONS;
    for (var d = index % DIRECTIONS; inside && part < RUNS && d < DIRECTIONS;
        d += TEXEL_GROUP_SIZE) {
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
        let run = march_run(part, RUNS, n);
        for (var s = run.x; s < run.y; s++) {
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
        if RUNS > 1u {
            // Joined below, where the first run adds the ground behind the last.
            group_a[index] = l_2nd;
            group_b[index] = f_ms;
            run_transmittance[index] = throughput;
        } else if ground {
            l_2nd += throughput * ground_bounce(layer, r, mu_s, t_max, nu, albedo);
        }
    }
    if RUNS > 1u {
        workgroupBarrier();
        // The first run of each direction sums them all; the others add nothing more.
        l_2nd = vec4<f32>(0.0);
        f_ms = vec4<f32>(0.0);
        if inside && part == 0u {
            let d = index;
            let omega = sphere_direction((d / half) * n_dir + d % half, n_dir);
            var throughput = vec4<f32>(1.0);
            for (var k = 0u; k < RUNS; k++) {
                let j = index + k * DIRECTIONS;
                l_2nd += throughput * group_a[j];
                f_ms += throughput * group_b[j];
                throughput *= run_transmittance[j];
            }
            if hits_ground(h, omega.z) {
                let nu = dot(omega, sun);
                l_2nd += throughput
                    * ground_bounce(layer, r, mu_s, distance_to_ground(h, omega.z), nu, albedo);
            }
        }
        // The sums below rewrite group_a and group_b.
        workgroupBarrier();
    }
    let sums = group_sums(TEXEL_GROUP_SIZE, index, l_2nd, f_ms);
    if inside && index == 0u {
        let count = f32(n_dir * half);
        let psi = (sums[0] / count) / (1.0 - sums[1] / count);
        let size = MULTIPLE_SCATTERING_SIZE;
        multiple_scattering_lut[(layer * size.y + id.y) * size.x + id.x] = psi;
    }
}

// The sunlit ground's bounce seen at the end of a ray of length t_max that hits it, per unit
// of the transmittance to there.
fn ground_bounce(layer: u32, r: f32, mu_s: f32, t_max: f32, nu: f32, albedo: vec4<f32>) -> vec4<f32> {
    let mu_s_g = (r * mu_s + t_max * nu) / bottom_radius();
    let sun_t = sun_transmittance(layer, 0.0, mu_s_g);
    return sun_t * max(mu_s_g, 0.0) * albedo / PI;
}
