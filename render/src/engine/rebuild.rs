//! A new atmosphere's tables: built whole in the frame that asks, or a slice per frame while
//! the last complete ones stay on screen.

use super::*;

impl Engine {
    /// The tables' buffers of a new atmosphere for `key`, its inputs uploaded.
    pub(super) fn build_state(&mut self, scene: &Scene, key: AtmosphereKey) -> AtmosphereState {
        let Some(gpu) = gpu_method(key.method) else {
            unreachable!("the caller checked the model is a real-time one");
        };
        let params = state_params(scene, &key);
        let model_constants = (gpu.constants)(&params);
        let i = self.pipelines_of(gpu);
        let tables = TableBuffers::new(&self.device, &self.pipelines[i], gpu.info(), &params);
        upload_batches(&self.queue, &tables, &params, key.method, scene);
        self.queue.write_buffer(
            &tables.profile,
            0,
            bytemuck::cast_slice(&uniforms::profile(&params)),
        );
        self.queue.write_buffer(
            &tables.mie_phase,
            0,
            bytemuck::cast_slice(&uniforms::mie_phase_rows(&params)),
        );
        AtmosphereState {
            key,
            params,
            tables,
            noon_white: std::sync::OnceLock::new(),
            model_constants,
            moving_sky: MovingSky::default(),
        }
    }

    /// A rebuild of everything `scene` draws with its new atmosphere `key`, to run in slices.
    pub(super) fn start_rebuild(
        &mut self,
        scene: &Scene,
        view: &View,
        gpu: &'static GpuMethod,
        key: AtmosphereKey,
        size: [u32; 2],
    ) -> Rebuild {
        let method = key.method;
        let mut state = self.build_state(scene, key);
        let frame = FrameSetup::new(scene, view, &state, gpu);
        self.queue
            .write_buffer(&state.tables.globals, 0, bytemuck::bytes_of(&frame.globals));
        let p = self.pipelines_of(gpu);
        let pipelines = &self.pipelines[p];
        let target = Target::new(&self.device, pipelines, &state.tables, size, self.sky_tile);
        let mut deferred = vec![false; pipelines.len()];
        // A rebuild draws its view at full resolution, and builds the moving sky of a march
        // per pixel where frames in motion are drawn in tiles (as if in motion): otherwise the
        // first of them would build it whole, in one frame, at a small share of the cost of
        // the still frame the rebuild draws anyway.
        let situation = frame.situation(frame.shows_ground(view), self.sky_tile > 1);
        let run = plan(
            &pipelines.method,
            Inputs::ALL,
            &situation,
            self.unwanted(),
            &mut deferred,
        );
        state.moving_sky.complete = pipelines
            .moving_sky_pass()
            .is_some_and(|m| run.contains(&m));
        let run = with_order_loop(&run, pipelines, state.params.scattering_orders);
        let variants = frame.variants(pipelines, scene, view);
        let layers = state.params.batches.len() as u32;
        let total_units = state.tables.bytes().div_ceil(CLEAR_UNIT_BYTES)
            + run
                .iter()
                .map(|s| u64::from(units(grid(pipelines, s.pass, layers, size))))
                .sum::<u64>();
        Rebuild {
            state,
            target,
            snapshot: frame.snapshot,
            deferred,
            variants,
            run,
            next: (0, 0),
            cleared: 0,
            units: self
                .slice_units
                .iter()
                .find(|(m, u)| *m == method && u.len() == pipelines.len() + 1)
                .map_or_else(|| vec![1; pipelines.len() + 1], |(_, u)| u.clone()),
            in_flight: None,
            done_units: 0,
            total_units,
            shortest_s: f64::INFINITY,
        }
    }

    /// Runs the next slice of the rebuild under way once the last one has finished. Returns
    /// its progress, or None when every slice has finished.
    pub(super) fn advance_rebuild(&mut self, slicing: Slicing) -> Option<RebuildProgress> {
        let _ = self.device.poll(wgpu::PollType::Poll);
        let gpu = gpu_method(self.rebuild.as_ref()?.state.key.method)?;
        let p = self.pipelines_of(gpu);
        let r = self.rebuild.as_mut()?;
        if let Some((clock, pass, count, half_row)) = &r.in_flight {
            if !clock.finished() {
                return Some(r.progress());
            }
            // Aim the pass's next slice at the target time from how long this one took.
            let target = slicing.target.as_secs_f64();
            let steered = clock.steer(*count, &mut r.shortest_s, target);
            r.units[*pass] = if target <= 0.0 { *half_row } else { steered };
            r.in_flight = None;
        }
        let clearing = r.units.len() - 1;
        let table_bytes = r.state.tables.bytes();
        if r.cleared < table_bytes {
            let count = r.units[clearing];
            let mut encoder = self.device.create_command_encoder(&Default::default());
            let cleared =
                r.state
                    .tables
                    .clear(&mut encoder, r.cleared, u64::from(count) * CLEAR_UNIT_BYTES);
            let clock = SliceClock::start(&self.device, &self.queue, slicing.alone, || {
                self.queue.submit([encoder.finish()]);
            });
            r.cleared += cleared;
            // The units zeroed, not those asked for: the last piece is usually short, and the
            // next slice is sized from what this one did.
            let units = cleared.div_ceil(CLEAR_UNIT_BYTES);
            r.in_flight = Some((clock, clearing, u32::try_from(units).unwrap_or(count), 16));
            r.done_units += units;
            return Some(r.progress());
        }
        let (k, unit) = r.next;
        let &step = r.run.get(k)?;
        let pass = step.pass;
        let variant = self.pipelines[p].with_constant(
            pass,
            r.variants[pass],
            Constant::FirstOrder,
            step.first_order(),
        );
        self.pipelines[p].ensure(&self.device, pass, variant);
        let layers = r.state.params.batches.len() as u32;
        let pipelines = &self.pipelines[p];
        let grid = grid(pipelines, pass, layers, r.target.size);
        let (_, _, count) = slice(grid, unit, r.units[pass]);
        let encoder = Encoder {
            device: &self.device,
            queue: &self.queue,
            pipelines,
            tables: &r.state.tables,
            target: &r.target,
            next_moving_sky: None,
        };
        let (origin, groups, _) = slice(grid, unit, count);
        let work = Work {
            pass,
            variant,
            origin,
            groups,
            tiles: TilePhase::None,
        };
        let clock = SliceClock::start(&self.device, &self.queue, slicing.alone, || {
            encoder.submit(&[work], None, false);
        });
        r.in_flight = Some((clock, pass, count, grid[0].div_ceil(2)));
        r.done_units += u64::from(count);
        r.next = if unit + count >= units(grid) {
            (k + 1, 0)
        } else {
            (k, unit + count)
        };
        Some(r.progress())
    }
}

/// The optics of an atmosphere for `key`. Sunlight at 1 AU: the sky pass scales the view to
/// the scene's distance (`SunSettings::sunlight_scale`), so a sun placed by date keeps its
/// tables all year.
pub(super) fn state_params(scene: &Scene, key: &AtmosphereKey) -> Params {
    Params::new(
        &Atmosphere::new(&key.settings),
        key.wavelengths,
        key.quality,
    )
    .with_render(&scene.render)
}

/// Uploads the optics of every batch of four wavelengths (`batches` in the shaders), with the
/// rows `method` computes for the sun at `scene`'s camera where it has them
/// (`GpuMethod::batch_rows`).
pub(super) fn upload_batches(
    queue: &wgpu::Queue,
    tables: &TableBuffers,
    params: &Params,
    method: Method,
    scene: &Scene,
) {
    let rows = gpu_method(method).and_then(|g| g.batch_rows);
    let mu_s = rows.map_or(0.0, |_| {
        let camera = Camera::new(
            &scene.camera,
            params.bottom_radius_m,
            Projection::Perspective,
        );
        viewpoint(scene, &camera).mu_s
    });
    let batches = uniforms::batches(params, rows, mu_s);
    queue.write_buffer(&tables.batches, 0, bytemuck::cast_slice(&batches));
}
