// The entry point of every model's sky pass, appended after the pass's file, which defines
// `radiance(layer, dir)`: a batch's radiance of the sky and the ground along a world direction
// from the camera, and, in the model's common files, `sun_through_atmosphere(layer, h, mu_s)`:
// the transmittance along the sun's own ray (shared/sun_disk.wgsl for the table-based models).
// The sun's disk is added here, averaged over the pixel (twin of model::methods::render_with). Sums the
// batches into linear sRGB (Y = ∫ȳL dλ) and writes coverage in alpha (0 outside the projection).

@compute @workgroup_size(WORKGROUP_SIZE, WORKGROUP_SIZE, 1)
fn main(@builtin(global_invocation_id) invocation: vec3<u32>) {
    let id = dispatched(invocation);
    if any(id.xy >= globals.view.xy) {
        return;
    }
    let x = f32(id.x) + 0.5;
    let y = f32(id.y) + 0.5;
    let ray = camera_ray(x, y);
    if ray.w == 0.0 {
        textureStore(radiance_out, id.xy, vec4<f32>(0.0));
        return;
    }
    var disk = no_disk();
    if SUN_DISK {
        disk = sun_pixel(x, y);
    }
    var rgb = vec3<f32>(0.0);
    for (var layer = 0u; layer < batch_count(); layer++) {
        var l = radiance(layer, ray.xyz);
        if SUN_DISK && disk.reaches {
            let sun = sun_through_atmosphere(layer, globals.camera_position.w, globals.sun.w);
            l += batches[layer].solar_irradiance * sun
                * disk_radiance(disk, batches[layer].wavelengths_nm);
        }
        rgb += vec3<f32>(dot(batches[layer].to_srgb_r, l), dot(batches[layer].to_srgb_g, l),
            dot(batches[layer].to_srgb_b, l));
    }
    textureStore(radiance_out, id.xy, vec4<f32>(rgb, 1.0));
}
