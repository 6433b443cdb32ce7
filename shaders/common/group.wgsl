// Sums across a workgroup, for passes dispatched one workgroup per texel
// (render::methods::Dispatch::TexelGroups), whose invocations share the texel's directions.

var<workgroup> group_a: array<vec4<f32>, TEXEL_GROUP_SIZE>;
var<workgroup> group_b: array<vec4<f32>, TEXEL_GROUP_SIZE>;

// The workgroup's sums of every invocation's a and b, returned to each invocation; `index` is
// the invocation's local_invocation_index (workgroups of TEXEL_GROUP_SIZE). Call it from uniform control flow (it waits at
// barriers): a tree of log2(TEXEL_GROUP_SIZE) steps.
fn group_sums(index: u32, a: vec4<f32>, b: vec4<f32>) -> array<vec4<f32>, 2> {
    group_a[index] = a;
    group_b[index] = b;
    workgroupBarrier();
    for (var stride = TEXEL_GROUP_SIZE / 2u; stride > 0u; stride /= 2u) {
        if index < stride {
            group_a[index] += group_a[index + stride];
            group_b[index] += group_b[index + stride];
        }
        workgroupBarrier();
    }
    return array<vec4<f32>, 2>(group_a[0], group_b[0]);
}
