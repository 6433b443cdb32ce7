// Sums across a workgroup, for the passes dispatched one workgroup per texel whose invocations
// share the texel's directions (render::methods::Dispatch::TexelGroups and TexelRuns):
// workgroups of TEXEL_GROUP_SIZE (Hillaire's multiple scattering, which splits each
// direction's march when the group has twice as many invocations as directions, and sums
// its run of texels' L_2nd in an array of its own beside group_b), or WIDE_GROUP_SIZE (his
// ground irradiance, whose 128 directions need the wider group for that). Those passes keep
// each run's partial results in group_a and group_b before the sums.

const WIDE_GROUP_SIZE: u32 = TEXEL_GROUP_SIZE * MARCH_SPLIT;

var<workgroup> group_a: array<vec4<f32>, WIDE_GROUP_SIZE>;
var<workgroup> group_b: array<vec4<f32>, WIDE_GROUP_SIZE>;

// The sums of every invocation's a and b over a workgroup of `size` invocations (a power of
// two, at most WIDE_GROUP_SIZE), returned to each; `index` is the invocation's
// local_invocation_index. Call it from uniform control flow with a constant size (it waits at
// barriers): a tree of log2(size) steps.
fn group_sums(size: u32, index: u32, a: vec4<f32>, b: vec4<f32>) -> array<vec4<f32>, 2> {
    group_a[index] = a;
    group_b[index] = b;
    workgroupBarrier();
    for (var stride = size / 2u; stride > 0u; stride /= 2u) {
        if index < stride {
            group_a[index] += group_a[index + stride];
            group_b[index] += group_b[index + stride];
        }
        workgroupBarrier();
    }
    return array<vec4<f32>, 2>(group_a[0], group_b[0]);
}

// Marches split across invocations, for passes of one invocation per texel whose tables have
// fewer texels than a GPU has invocations in flight (the transmittance, Hillaire's sky view):
// workgroups of WORKGROUP_SIZE × WORKGROUP_SIZE texels × MARCH_SPLIT parts, each part
// marching a contiguous run of its texel's steps; the parts are then joined in the order a
// single march adds them. MARCH_SPLIT (generated) is 1 on a CPU adapter, where the join is
// compiled away and each invocation marches all its steps, as an unsplit march does.

const SPLIT_TEXELS: u32 = WORKGROUP_SIZE * WORKGROUP_SIZE;

var<workgroup> split_a: array<vec4<f32>, SPLIT_TEXELS * MARCH_SPLIT>;
var<workgroup> split_b: array<vec4<f32>, SPLIT_TEXELS * MARCH_SPLIT>;

// The texel (x, y, batch) of an invocation of such a pass, workgroups one deep in z.
fn dispatched_split(workgroup: vec3<u32>, local: vec3<u32>) -> vec3<u32> {
    return vec3<u32>(workgroup.xy * WORKGROUP_SIZE + local.xy, workgroup.z) + origin.xyz;
}

// Steps [first, last) of n for run `part` of `parts` of a march.
fn march_run(part: u32, parts: u32, n: u32) -> vec2<u32> {
    return vec2<u32>(part * n / parts, (part + 1u) * n / parts);
}

// The sum over a texel's parts of each part's `value`; `index` is local_invocation_index.
// Call it from uniform control flow (it waits at a barrier).
fn split_sum(index: u32, value: vec4<f32>) -> vec4<f32> {
    if MARCH_SPLIT == 1u {
        return value;
    }
    split_a[index] = value;
    workgroupBarrier();
    var sum = vec4<f32>(0.0);
    for (var k = 0u; k < MARCH_SPLIT; k++) {
        sum += split_a[index % SPLIT_TEXELS + k * SPLIT_TEXELS];
    }
    return sum;
}
