// Pass: multiple-scattering table Ψ_ms(h, mu_s) = L_2nd / (1 − f_ms), per unit solar irradiance
// (Hillaire 2020 §5.5), with an isotropic phase and the sunlit ground bounce, over the directions
// on one side of the sun's vertical plane (their mirror images see the same). One workgroup per
// run of TEXEL_RUN texels along a row (prelude::texel_run): the rays from one altitude are the
// same for every sun angle, and only the sunlight along them differs, so each ray is marched
// once for the run (a CPU adapter's 4; a GPU keeps one texel a workgroup, as Hillaire's own
// pass does, for the invocations in flight). The invocations share the directions; a workgroup
// of more invocations than directions (64 on a GPU, for 32) splits each direction's march into
// RUNS runs of steps, joined in order before the sums.

// The directions marched: one side of the sun's vertical plane.
const DIRECTIONS: u32 = MULTIPLE_SCATTERING_DIRECTIONS_SQRT * MULTIPLE_SCATTERING_DIRECTIONS_SQRT / 2u;
const RUNS: u32 = select(1u, TEXEL_GROUP_SIZE / DIRECTIONS, TEXEL_GROUP_SIZE >= 2u * DIRECTIONS);

// Each invocation's run's transmittance, f_ms (in group_b) and L_2nd for each texel of the run.
var<workgroup> run_transmittance: array<vec4<f32>, TEXEL_GROUP_SIZE>;
var<workgroup> run_l_2nd: array<array<vec4<f32>, TEXEL_GROUP_SIZE>, TEXEL_RUN>;

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
    let size = MULTIPLE_SCATTERING_SIZE;
    let id = dispatched_texel(workgroup);
    let first = id.x * TEXEL_RUN;
    let inside = first < size.x && id.y < size.y && id.z < batch_count();
    let layer = min(id.z, batch_count() - 1u);
    // The run's texels past the table's edge (none where the run divides its width) repeat
    // its last and are not written.
    var mu_s: array<f32, TEXEL_RUN>;
    var sun: array<vec3<f32>, TEXEL_RUN>;
    var h = 0.0;
    for (var c = 0u; c < TEXEL_RUN; c++) {
        let x = min(first + c, size.x - 1u);
        let hm = multiple_scattering_h_mu_s_from_texel(vec2<f32>(f32(x), f32(id.y)));
        h = hm.x;
        mu_s[c] = hm.y;
        sun[c] = local_sun(hm.y);
    }
    let r = bottom_radius() + h;
    let isotropic = 1.0 / (4.0 * PI);
    let b = batches[layer];
    let albedo = b.ground_albedo;
    let n_dir = MULTIPLE_SCATTERING_DIRECTIONS_SQRT;
    let n = globals.steps_a.y;
    var l_2nd: array<vec4<f32>, TEXEL_RUN>;
    var f_ms = vec4<f32>(0.0);
    // One side of the sun's vertical plane: a mirror direction has the same mu and nu.
    let half = n_dir / 2u;
    let part = index / DIRECTIONS;
    for (var d = index % DIRECTIONS; inside && part < RUNS && d < DIRECTIONS;
        d += TEXEL_GROUP_SIZE) {
        let omega = sphere_direction((d / half) * n_dir + d % half, n_dir);
        let mu = omega.z;
        let ground = hits_ground(h, mu);
        var t_max: f32;
        if ground {
            t_max = distance_to_ground(h, mu);
        } else {
            t_max = distance_to_top(h, mu);
        }
        var nu: array<f32, TEXEL_RUN>;
        for (var c = 0u; c < TEXEL_RUN; c++) {
            nu[c] = dot(omega, sun[c]);
        }
        var throughput = vec4<f32>(1.0);
        let run = march_run(part, RUNS, n);
        for (var s = run.x; s < run.y; s++) {
            let seg = march_segment(SPACING_QUADRATIC, 0.0, t_max, s, n);
            let ts = 0.5 * (seg.x + seg.y);
            let dt = seg.y - seg.x;
            let at = altitude_along(h, mu, ts);
            let m = medium(b, at.x);
            let weight = throughput * segment_weight(m.extinction, dt);
            let sca = m.rayleigh_scattering + m.aerosol_scattering;
            let lit = weight * sca * isotropic;
            for (var c = 0u; c < TEXEL_RUN; c++) {
                let mu_s_t = (r * mu_s[c] + ts * nu[c]) / at.y;
                l_2nd[c] += lit * sun_transmittance(layer, at.x, mu_s_t);
            }
            f_ms += weight * sca;
            throughput *= exp(-m.extinction * dt);
        }
        if RUNS > 1u {
            // Joined below, where the first run adds the ground behind the last.
            for (var c = 0u; c < TEXEL_RUN; c++) {
                run_l_2nd[c][index] = l_2nd[c];
            }
            group_b[index] = f_ms;
            run_transmittance[index] = throughput;
        } else if ground {
            for (var c = 0u; c < TEXEL_RUN; c++) {
                l_2nd[c] += throughput * ground_bounce(layer, r, mu_s[c], t_max, nu[c], albedo);
            }
        }
    }
    if RUNS > 1u {
        workgroupBarrier();
        // The first run of each direction sums them all; the others add nothing more.
        l_2nd = array<vec4<f32>, TEXEL_RUN>();
        f_ms = vec4<f32>(0.0);
        if inside && part == 0u {
            let d = index;
            let omega = sphere_direction((d / half) * n_dir + d % half, n_dir);
            var throughput = vec4<f32>(1.0);
            for (var k = 0u; k < RUNS; k++) {
                let j = index + k * DIRECTIONS;
                for (var c = 0u; c < TEXEL_RUN; c++) {
                    l_2nd[c] += throughput * run_l_2nd[c][j];
                }
                f_ms += throughput * group_b[j];
                throughput *= run_transmittance[j];
            }
            if hits_ground(h, omega.z) {
                let t_max = distance_to_ground(h, omega.z);
                for (var c = 0u; c < TEXEL_RUN; c++) {
                    let nu = dot(omega, sun[c]);
                    l_2nd[c] += throughput * ground_bounce(layer, r, mu_s[c], t_max, nu, albedo);
                }
            }
        }
        // The sums below rewrite run_l_2nd and group_b.
        workgroupBarrier();
    }
    // The sums over the workgroup, in the tree of group_sums (common/group.wgsl) for each texel.
    for (var c = 0u; c < TEXEL_RUN; c++) {
        run_l_2nd[c][index] = l_2nd[c];
    }
    group_b[index] = f_ms;
    workgroupBarrier();
    for (var stride = TEXEL_GROUP_SIZE / 2u; stride > 0u; stride /= 2u) {
        if index < stride {
            for (var c = 0u; c < TEXEL_RUN; c++) {
                run_l_2nd[c][index] += run_l_2nd[c][index + stride];
            }
            group_b[index] += group_b[index + stride];
        }
        workgroupBarrier();
    }
    if inside && index == 0u {
        let count = f32(n_dir * half);
        let escape = 1.0 - group_b[0] / count;
        for (var c = 0u; c < TEXEL_RUN && first + c < size.x; c++) {
            let psi = (run_l_2nd[c][0] / count) / escape;
            multiple_scattering_lut[(layer * size.y + id.y) * size.x + first + c] = psi;
        }
    }
}

// The sunlit ground's bounce seen at the end of a ray of length t_max that hits it, per unit
// of the transmittance to there.
fn ground_bounce(layer: u32, r: f32, mu_s: f32, t_max: f32, nu: f32, albedo: vec4<f32>) -> vec4<f32> {
    let mu_s_g = (r * mu_s + t_max * nu) / bottom_radius();
    let sun_t = sun_transmittance(layer, 0.0, mu_s_g);
    return sun_t * max(mu_s_g, 0.0) * albedo / PI;
}
