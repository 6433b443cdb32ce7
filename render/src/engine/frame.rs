//! One frame: from the scene to the passes encoded (`render_frame`), and the step of the moving
//! sky built in slices.

use super::*;

impl Engine {
    pub(super) fn render_frame(&mut self, scene: &Scene, view: &View) -> Result<(), EngineError> {
        let max = self.device.limits().max_texture_dimension_2d;
        if view.width > max || view.height > max {
            return Err(EngineError::ViewTooLarge(view.width, view.height, max));
        }
        let method = scene.render.method;
        let drawable = match methods::info(method).cannot_draw(scene) {
            Some(why) => Err(EngineError::from(why)),
            None => gpu_method(method).ok_or_else(|| {
                CannotDraw::NotRealtime(methods::info(method).id, methods::realtime_ids()).into()
            }),
        };
        let gpu = match drawable {
            Ok(gpu) => gpu,
            Err(e) => {
                // A rebuild under way is for a scene that is no longer asked for.
                self.rebuild = None;
                return Err(e);
            }
        };
        let key = AtmosphereKey {
            settings: scene.atmosphere.clone(),
            method,
            wavelengths: scene.render.wavelengths,
            quality: scene.render.quality,
            scattering_orders: scene.render.scattering_orders,
            fitted_constants: scene.render.fitted_constants,
            cie_sky_type: (method == Method::CieStandardSky).then_some(scene.render.cie_sky_type),
        };
        let size = [view.width.max(1), view.height.max(1)];
        let current = self.atmosphere.as_ref().is_some_and(|a| a.key == key);
        // Where no table holds the ground albedo, a change of it alone redraws the view with
        // the tables on screen (Elek's ground reflects nothing into his tables).
        let albedo_only = !current
            && !gpu.info().tables_hold_the_albedo()
            && self
                .atmosphere
                .as_ref()
                .is_some_and(|a| a.key.without_albedo() == key.without_albedo());
        let mut rebuilt = false;
        let mut progress = None;
        let mut rebuild_done = false;
        if current {
            // The scene went back to what is on screen: a rebuild under way is moot.
            self.rebuild = None;
        } else if albedo_only {
            self.rebuild = None;
            // A moving sky under way would be published half with the old albedo.
            self.drop_moving_sky_job();
            if let Some(state) = self.atmosphere.as_mut() {
                state.params = state_params(scene, &key);
                state.model_constants = (gpu.constants)(&state.params);
                upload_batches(&self.queue, &state.tables, &state.params, key.method, scene);
                state.key = key;
            }
        } else if let Some(slice) = self.slicing {
            // Build the new tables and view a slice per frame; the old ones, if any, stay on
            // screen. A held rebuild waits where it is, one not yet started before its buffers
            // and pipelines are made.
            let started = self.rebuild.as_ref().is_some_and(|r| r.state.key == key);
            let advanced = if self.rebuild_held {
                Some(match &self.rebuild {
                    Some(r) if started => r.progress(),
                    _ => RebuildProgress { done: 0, total: 1 },
                })
            } else {
                if !started {
                    self.rebuild = Some(self.start_rebuild(scene, view, gpu, key, size));
                }
                self.advance_rebuild(slice)
            };
            match advanced {
                Some(p) => progress = Some(p),
                None => {
                    if let Some(r) = self.rebuild.take() {
                        rebuild_done = true;
                        self.slice_units.retain(|(m, _)| *m != r.state.key.method);
                        self.slice_units.push((r.state.key.method, r.units));
                        self.atmosphere = Some(r.state);
                        self.target = Some(r.target);
                        self.last = Some(r.snapshot);
                        self.deferred = r.deferred;
                    }
                }
            }
        } else {
            self.rebuild = None;
            self.refine = None;
            self.select(gpu);
            self.atmosphere = Some(self.build_state(scene, key));
            rebuilt = true;
        }
        // The model on screen: the scene's, or the previous one while a rebuild is under way;
        // none while the first is built in slices, which the frame only reports.
        let Some(gpu) = self
            .atmosphere
            .as_ref()
            .and_then(|a| gpu_method(a.key.method))
        else {
            self.stats = FrameStats {
                method,
                rebuild: progress,
                ..FrameStats::default()
            };
            return Ok(());
        };
        self.select(gpu);
        let Some(state) = self.atmosphere.as_ref() else {
            unreachable!("the atmosphere was just built");
        };
        let mut frame = FrameSetup::new(scene, view, state, gpu);
        let mut changed = frame
            .snapshot
            .changes_from(self.last.as_ref())
            .union(std::mem::replace(&mut self.forced, Inputs::NONE));
        if rebuilt {
            // New tables, empty: every pass runs, whatever of the atmosphere changed (the
            // ground albedo alone, for a model whose tables hold it).
            changed = changed.union(Inputs::ATMOSPHERE);
        }
        if rebuild_done {
            // The rebuild drew its view at full resolution.
            self.tiled_on_screen = false;
            self.radiance_current = true;
        }
        // The view is drawn again at full resolution by a still frame after one in tiles, and
        // by a frame that changes only the display or meters while the radiance image is not
        // the one on screen (a frame in tiles left it unwritten): the display and meter passes
        // would read it. The latter holds during a rebuild in slices too.
        let display_only = Inputs::DISPLAY.union(changed) == Inputs::DISPLAY;
        let still_after_tiles = self.tiled_on_screen && progress.is_none() && changed.is_empty();
        let radiance_read =
            !self.radiance_current && (changed.intersects(Inputs::DISPLAY) || self.metering);
        let refine = display_only && (still_after_tiles || radiance_read);
        if refine {
            changed = changed.union(Inputs::VIEW_SIZE);
        }
        // Where the engine slices its work, a still frame after tiles is drawn a slice per
        // frame; anything else that happens meanwhile drops it (a frame in motion draws in
        // tiles again, a change of the display needs the whole radiance now).
        let refine_in_slices = match self.slicing {
            Some(slicing) if still_after_tiles && !radiance_read && !rebuilt => Some(slicing),
            _ => None,
        };
        if refine_in_slices.is_none() {
            self.refine = None;
        }
        // A frame whose inputs did not change is a still one (the frame that swaps in a
        // rebuild's tables and view, drawn at full resolution, and those after it): it builds
        // no moving sky.
        frame.sky_tile = if refine || changed.is_empty() {
            1
        } else {
            self.sky_tile
        };
        frame.write_radiance = frame.sky_tile <= 1 || self.metering;
        frame.bands = self.view_bands;
        if rebuilt || self.target.as_ref().is_none_or(|t| t.size != size) {
            // New images: every pass that writes them must run.
            changed = changed.union(Inputs::VIEW_SIZE);
            self.target = Some(Target::new(
                &self.device,
                &self.pipelines[0],
                &state.tables,
                size,
                self.sky_tile,
            ));
        }
        if !changed.is_empty() {
            self.queue
                .write_buffer(&state.tables.globals, 0, bytemuck::bytes_of(&frame.globals));
            // A model's rows for the sun at the camera (Hosek–Wilkie's coefficients), when
            // what they depend on changed.
            let rows_inputs = Inputs::VIEWPOINT
                .union(Inputs::ATMOSPHERE)
                .union(Inputs::GROUND_ALBEDO);
            if gpu.batch_rows.is_some() && changed.intersects(rows_inputs) {
                upload_batches(&self.queue, &state.tables, &state.params, gpu.method, scene);
            }
        }
        let pipelines = &self.pipelines[0];
        if rebuilt || self.deferred.len() != pipelines.len() {
            self.deferred = vec![false; pipelines.len()];
        }
        // Whether the view shows the ground matters only to a frame with stale passes.
        let stale = !changed.is_empty() || self.deferred.iter().any(|&d| d);
        let ground = stale && frame.shows_ground(view);
        let mut run = plan(
            &pipelines.method,
            changed,
            &frame.situation(ground, frame.sky_tile > 1),
            self.unwanted(),
            &mut self.deferred,
        );
        let layers = state.params.batches.len() as u32;
        // Where the engine slices its work and a moving sky is complete, a new one is built in
        // slices (`MovingSky`) and the frame reads the complete one: in motion, where the frame
        // would build it, and in a still frame where one was left stale (the sun let go while
        // the last was being built), so that the next motion finds it caught up. While one is
        // being built the pass stays stale, to start again once it is complete.
        let moving_sky_pass = pipelines.moving_sky_pass();
        let mut start_moving_sky = None;
        let in_slices = self.slicing.is_some()
            && state.moving_sky.complete
            && state.tables.next_moving_sky.is_some();
        if let Some(m) = moving_sky_pass.filter(|&m| {
            in_slices
                && (run.contains(&m) || (self.deferred[m] && self.sky_tile > 1 && !frame.above))
        }) {
            run.retain(|&i| i != m);
            if state.moving_sky.job.is_some() {
                self.deferred[m] = true;
            } else {
                self.deferred[m] = false;
                start_moving_sky = Some(
                    with_order_loop(&[m], pipelines, state.params.scattering_orders)
                        .into_iter()
                        .flat_map(|step| frame.work(pipelines, step, layers, scene, view))
                        .collect::<Vec<Work>>(),
                );
            }
        }
        let steps = with_order_loop(&run, pipelines, state.params.scattering_orders);
        let work: Vec<Work> = steps
            .iter()
            .flat_map(|&step| frame.work(pipelines, step, layers, scene, view))
            .collect();
        // A still frame in slices submits its next slice, or nothing while one is on the GPU;
        // `refined` once every slice has finished.
        let mut refined = false;
        let work = match refine_in_slices {
            Some(slicing) => {
                // Runs the callback that marks the slice in flight finished.
                let _ = self.device.poll(wgpu::PollType::Poll);
                let job = self.refine.get_or_insert_with(|| Slices::new(work));
                job.next_slice(slicing).unwrap_or_else(|| {
                    refined = true;
                    self.refine = None;
                    Vec::new()
                })
            }
            None => work,
        };
        // The steps that run this frame (all of them, but while a still frame is in slices).
        let steps: Vec<Step> = steps
            .into_iter()
            .filter(|s| work.iter().any(|w| w.pass == s.pass))
            .collect();
        let ran_pass = |i: usize| steps.iter().any(|s| s.pass == i);
        for w in &work {
            self.pipelines[0].ensure(&self.device, w.pass, w.variant);
        }
        let timings = match (&self.atmosphere, &self.target) {
            (Some(state), Some(target)) if !work.is_empty() => {
                let measure = self.measure.then_some(&self.timer);
                let encoder = Encoder {
                    device: &self.device,
                    queue: &self.queue,
                    pipelines: &self.pipelines[0],
                    tables: &state.tables,
                    target,
                    next_moving_sky: None,
                };
                let mut timings = Timings::default();
                let alone = refine_in_slices.is_some_and(|s| s.alone);
                let clock = SliceClock::start(&self.device, &self.queue, alone, || {
                    timings = encoder.submit(&work, measure, self.spans);
                });
                if let Some(job) = &mut self.refine {
                    job.submitted(clock, &work);
                }
                timings
            }
            _ => Timings::default(),
        };
        let timings_ms = timings.passes;
        let method_on_screen = state.key.method;
        let moving_sky = self.advance_moving_sky(
            start_moving_sky,
            &frame.globals,
            moving_sky_pass.is_some_and(ran_pass),
        );
        let pipelines = &self.pipelines[0];
        if pipelines
            .specs()
            .enumerate()
            .any(|(i, s)| s.writes.contains(&RADIANCE) && ran_pass(i))
            && self.refine.is_none()
        {
            self.tiled_on_screen = frame.sky_tile > 1;
            self.radiance_current = frame.write_radiance;
        }
        if refined {
            self.tiled_on_screen = false;
            self.radiance_current = true;
        }
        let names: Vec<&'static str> = pipelines.specs().map(|s| s.name).collect();
        let unwanted = self.unwanted();
        let is_table: Vec<bool> = pipelines.specs().map(|s| s.is_table()).collect();
        // Each pass once, in order, however often the order loop ran it; its times summed.
        let ran: Vec<usize> = (0..names.len()).filter(|&i| ran_pass(i)).collect();
        let timings_ms: Vec<(&'static str, f64)> = ran
            .iter()
            .filter(|&&i| timings_ms.iter().any(|(j, _)| *j == i))
            .map(|&i| {
                let total = timings_ms
                    .iter()
                    .filter(|(j, _)| *j == i)
                    .map(|(_, ms)| ms)
                    .sum();
                (names[i], total)
            })
            .collect();
        self.last = Some(frame.snapshot);
        self.stats = FrameStats {
            method: method_on_screen,
            // The tiles are those of the pass that draws the view's radiance, when it ran.
            sky_tile: if ran.iter().any(|&i| {
                pipelines
                    .specs()
                    .nth(i)
                    .is_some_and(|s| !s.is_table() && s.writes.contains(&RADIANCE))
            }) {
                frame.sky_tile
            } else {
                1
            },
            timing_source: (self.measure && !steps.is_empty()).then(|| self.timing_source()),
            skipped: (0..names.len())
                .filter(|i| !ran.contains(i) && !unwanted.contains(&names[*i]))
                .map(|i| names[i])
                .collect(),
            tables_run: ran
                .iter()
                .filter(|&&i| is_table[i])
                .map(|&i| names[i])
                .collect(),
            run: ran.iter().map(|&i| names[i]).collect(),
            dispatched: steps.len(),
            passes: names
                .iter()
                .copied()
                .filter(|n| !unwanted.contains(n))
                .collect(),
            timings_ms,
            spans_ms: timings.spans,
            rebuild: progress,
            rebuild_done,
            moving_sky,
        };
        Ok(())
    }

    /// The next moving sky of the model on screen (`MovingSky`): started from `globals` when
    /// `start` holds its dispatches, its next slice submitted once the last has finished, and
    /// once every slice has, copied over the one the sky pass reads. `built_whole`: the frame
    /// built the moving sky itself.
    pub(super) fn advance_moving_sky(
        &mut self,
        start: Option<Vec<Work>>,
        globals: &Globals,
        built_whole: bool,
    ) -> MovingSkyStep {
        let (Some(state), Some(target)) = (self.atmosphere.as_mut(), self.target.as_ref()) else {
            return MovingSkyStep::None;
        };
        let moving = &mut state.moving_sky;
        moving.complete |= built_whole;
        let next = state.tables.next_moving_sky.as_ref();
        if let (Some(work), Some(next)) = (start, next) {
            self.queue
                .write_buffer(&next.globals, 0, bytemuck::bytes_of(globals));
            moving.job = Some(Slices::steered(work, moving.units, moving.shortest_s));
        }
        let (Some(slicing), Some(job), Some(next)) = (self.slicing, moving.job.as_mut(), next)
        else {
            return MovingSkyStep::None;
        };
        // Runs the callback that marks the slice in flight finished.
        let _ = self.device.poll(wgpu::PollType::Poll);
        match job.next_slice(slicing) {
            Some(work) if work.is_empty() => MovingSkyStep::Waiting,
            Some(work) => {
                for w in &work {
                    self.pipelines[0].ensure(&self.device, w.pass, w.variant);
                }
                let encoder = Encoder {
                    device: &self.device,
                    queue: &self.queue,
                    pipelines: &self.pipelines[0],
                    tables: &state.tables,
                    target,
                    next_moving_sky: Some(next),
                };
                let clock = SliceClock::start(&self.device, &self.queue, slicing.alone, || {
                    encoder.submit(&work, None, false);
                });
                job.submitted(clock, &work);
                MovingSkyStep::Slice
            }
            None => {
                (moving.units, moving.shortest_s) = (job.units, job.shortest_s);
                moving.job = None;
                let mut encoder = self.device.create_command_encoder(&Default::default());
                state.tables.publish_next_moving_sky(&mut encoder);
                self.queue.submit([encoder.finish()]);
                MovingSkyStep::Published
            }
        }
    }

    /// Forgets the next moving sky being built, leaving the pass stale so that the next frame
    /// in motion builds it.
    pub(super) fn drop_moving_sky_job(&mut self) {
        let job = self
            .atmosphere
            .as_mut()
            .and_then(|a| a.moving_sky.job.take());
        if let (Some(_), Some(m)) = (
            job,
            self.pipelines.first().and_then(Pipelines::moving_sky_pass),
        ) {
            if let Some(d) = self.deferred.get_mut(m) {
                *d = true;
            }
        }
    }
}
