// The closed-form models' columns: ∫ exp(−h'/H) along the ray from altitude h along zenith
// cosine mu, for air and aerosol (their fitted scale heights in globals.model[1]), by the way's
// closed form of shared/exponential.wgsl: 2 Schuler, 3 Gałaj's Taylor, 4 Leenman's homogeneous
// shell. galaj_spline/columns.wgsl defines the same function from its mesh. Twin of
// ExponentialMedium::optical_depth's columns in SunRoute::optical_depth.

fn exponential_column(way: u32, h: f32, mu: f32, big_h: f32) -> f32 {
    if way == 2u {
        return schuler_chapman(h, mu, big_h);
    }
    if way == 4u {
        return homogeneous_shell(h, mu, big_h);
    }
    return galaj_taylor(h, mu, big_h);
}

fn columns_to_top(way: u32, h: f32, mu: f32) -> vec2<f32> {
    let fit = globals.model[1];
    var aerosol = 0.0;
    if fit.w > 0.0 {
        aerosol = exponential_column(way, h, mu, fit.z);
    }
    return vec2<f32>(exponential_column(way, h, mu, fit.x), aerosol);
}
