//! Haber (2005) on the GPU: the transmittance table, order 1 of the intensity volume
//! (`shaders/haber/first_order.wgsl`), then an order loop (`previous_order.wgsl`,
//! `next_order.wgsl`) gathering each order from the one before and adding it to the volume,
//! and `nishita_96`'s sky passes reading the volume. Its f64 twin is
//! `atmoscope_model::methods::haber`.

use super::nishita_96::{
    INTENSITY_MARCH, INTENSITY_VOLUME, INTENSITY_VOLUME_COMMON, ORDER_1, SKY_PASSES,
};
use super::{
    Dispatch, GpuMethod, PassSpec, Repeat, Resource, TRANSMITTANCE, TRANSMITTANCE_PASS, Table,
    read, shader,
};
use atmoscope_model::methods::haber;
use atmoscope_model::methods::shared::intensity_volume;
use atmoscope_model::scene::Method;

const DELTA: Resource = Resource::table(&intensity_volume::DELTA);
const PREVIOUS: Resource = Resource::table(&intensity_volume::PREVIOUS);

pub const METHODS: &[GpuMethod] = &[GpuMethod {
    method: Method::Haber,
    lowest_table_mu_s: None,
    common: &INTENSITY_VOLUME_COMMON,
    constants: haber::constants,
    batch_rows: None,
    passes: &[
        TRANSMITTANCE_PASS,
        PassSpec::table(
            "first-order",
            &[ORDER_1, INTENSITY_MARCH, shader!("haber/first_order.wgsl")],
            &[read(TRANSMITTANCE)],
            &[INTENSITY_VOLUME, DELTA, PREVIOUS],
            Dispatch::Volume(Table(&intensity_volume::TABLE)),
            Repeat::Once,
        ),
        PassSpec::table(
            "previous-order",
            &[shader!("haber/previous_order.wgsl")],
            &[read(DELTA)],
            &[PREVIOUS],
            Dispatch::Volume(Table(&intensity_volume::PREVIOUS)),
            Repeat::PerOrder,
        ),
        PassSpec::table(
            "next-order",
            &[INTENSITY_MARCH, shader!("haber/next_order.wgsl")],
            &[read(PREVIOUS), read(INTENSITY_VOLUME)],
            &[DELTA, INTENSITY_VOLUME],
            Dispatch::Volume(Table(&intensity_volume::DELTA)),
            Repeat::PerOrder,
        ),
        SKY_PASSES[0],
        SKY_PASSES[1],
        SKY_PASSES[2],
    ],
}];
