// Pass: the view's luminance histogram, pixels per bin of log10 cd/m² (twin of
// model::display::Histogram::of), which automatic exposure meters from and the explorer
// shows. Each workgroup counts in shared memory, then adds its counts to the view's.

var<workgroup> bins: array<atomic<u32>, HISTOGRAM_BINS>;

// Twin of model::display::histogram_bin.
fn histogram_bin(luminance: f32) -> u32 {
    let lo = HISTOGRAM_LOG10_RANGE.x;
    let hi = HISTOGRAM_LOG10_RANGE.y;
    let t = (log(max(luminance, 1e-30)) / log(10.0) - lo) / (hi - lo);
    return u32(clamp(floor(t * f32(HISTOGRAM_BINS)), 0.0, f32(HISTOGRAM_BINS - 1u)));
}

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>,
    @builtin(local_invocation_index) local: u32) {
    let id = dispatched(invocation);
    let threads = WORKGROUP_SIZE * WORKGROUP_SIZE;
    for (var i = local; i < HISTOGRAM_BINS; i += threads) {
        atomicStore(&bins[i], 0u);
    }
    workgroupBarrier();
    if all(id.xy < globals.view.xy) {
        let l = textureLoad(radiance_in, id.xy, 0);
        if l.a > 0.0 {
            let y = dot(SRGB_TO_Y, l.rgb) * MAX_LUMINOUS_EFFICACY_LM_PER_W;
            atomicAdd(&bins[histogram_bin(y)], 1u);
        }
    }
    workgroupBarrier();
    for (var i = local; i < HISTOGRAM_BINS; i += threads) {
        let c = atomicLoad(&bins[i]);
        if c > 0u {
            atomicAdd(&histogram[i], c);
        }
    }
}
