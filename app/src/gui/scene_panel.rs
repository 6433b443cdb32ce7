//! The Scene panel: every field of the scene as a control with its unit and a tooltip that
//! explains the physics in a sentence or two.

use super::exposure;
use super::state::Command;
use super::thumbnails::{SIZE as THUMBNAIL_SIZE, Thumbnails};
use crate::lessons::Section;
use crate::presets::SHIPPED;
use atmoscope_model::Scene;
use atmoscope_model::aerosol::AerosolType;
use atmoscope_model::ground::GroundType;
use atmoscope_model::methods::{self, cie_standard_sky};
use atmoscope_model::ozone::OzoneCrossSection;
use atmoscope_model::profiles::{AirProfile, OzoneProfile};
use atmoscope_model::scene::limits;
use atmoscope_model::scene::{
    AerosolPhase, FittedConstants, Method, OzoneColumn, Quality, SunSettings, ToneMap,
    WavelengthSet, WhiteBalance,
};
use atmoscope_model::solar_spectrum::SolarSpectrum;
use atmoscope_model::sun_position::DateTime;
use eframe::egui::{self, ComboBox, DragValue, Slider};

const MONTHS: [&str; 12] = [
    "January",
    "February",
    "March",
    "April",
    "May",
    "June",
    "July",
    "August",
    "September",
    "October",
    "November",
    "December",
];

/// Draws the panel, framing the section `highlight` (a lesson's invitation to try it) and
/// showing the presets with their thumbnails once loaded; returns the commands its controls
/// produced this frame.
pub fn show(
    ui: &mut egui::Ui,
    current: &Scene,
    meter: Option<&exposure::Reading>,
    highlight: Option<Section>,
    thumbnails: &Thumbnails,
) -> Vec<Command> {
    let mut commands = Vec::new();
    let mut s = current.clone();
    ui.heading("Scene");
    ComboBox::from_label("Preset")
        .selected_text("Load a preset…")
        .height(560.0)
        .show_ui(ui, |ui| {
            commands.push(Command::WantThumbnails);
            if thumbnails.loading() {
                ui.weak("drawing the thumbnails…");
            }
            if let Some(e) = &thumbnails.error {
                ui.colored_label(ui.visuals().error_fg_color, format!("no thumbnails: {e}"));
            }
            for (name, _) in SHIPPED {
                let label = name.trim_end_matches(".ron");
                let button = match thumbnails.get(name) {
                    Some(t) => egui::Button::image_and_text(
                        egui::Image::from_texture(egui::load::SizedTexture::new(
                            t.id(),
                            egui::vec2(THUMBNAIL_SIZE[0] as f32, THUMBNAIL_SIZE[1] as f32),
                        )),
                        label,
                    ),
                    None => egui::Button::new(label),
                };
                if ui.add(button.frame(false)).clicked() {
                    commands.push(Command::LoadPreset(name));
                    ui.close();
                }
            }
        })
        .response
        .on_hover_text("Scenes shipped with Atmoscope, each named for what it shows.");

    let section = |ui: &mut egui::Ui, which: Section, body: &mut dyn FnMut(&mut egui::Ui)| {
        let header =
            egui::CollapsingHeader::new(which.title()).default_open(which != Section::Rendering);
        if highlight == Some(which) {
            // The section a lesson invites the user to try: framed, and open.
            egui::Frame::group(ui.style())
                .stroke(egui::Stroke::new(2.0, ui.visuals().selection.bg_fill))
                .show(ui, |ui| {
                    ui.colored_label(ui.visuals().selection.bg_fill, "Try this section");
                    header.open(Some(true)).show(ui, |ui| body(ui));
                });
        } else {
            header.show(ui, |ui| body(ui));
        }
    };
    section(ui, Section::Aerosols, &mut |ui| aerosol(ui, &mut s));
    section(ui, Section::Ozone, &mut |ui| ozone(ui, &mut s));
    section(ui, Section::GroundAndAir, &mut |ui| {
        ground_and_air(ui, &mut s)
    });
    section(ui, Section::Sun, &mut |ui| sun(ui, &mut s));
    section(ui, Section::Camera, &mut |ui| camera(ui, &mut s));
    section(ui, Section::Rendering, &mut |ui| render(ui, &mut s, meter));
    s.tie_ozone_to_sun();

    if s != *current {
        commands.push(Command::SetScene(Box::new(s)));
    }
    commands
}

fn aerosol(ui: &mut egui::Ui, s: &mut Scene) {
    let a = &mut s.atmosphere.aerosol;
    let before = a.kind;
    ComboBox::from_label("Type")
        .selected_text(a.kind.label())
        .show_ui(ui, |ui| {
            for t in AerosolType::ALL {
                ui.selectable_value(&mut a.kind, t, t.label());
            }
        })
        .response
        .on_hover_text(
            "Aerosols are liquid or solid particles in the air. Their size and material decide how strongly they \
             scatter and absorb each colour: fine urban soot absorbs, coarse desert dust scatters almost greyly.",
        );
    if a.kind != before {
        a.aod550 = a.kind.default_aod550();
    }
    ui.add_enabled(
        a.kind != AerosolType::None,
        Slider::new(&mut a.aod550, limits::AOD550.range()).logarithmic(true).smallest_positive(0.001).text("AOD at 550 nm"),
    )
    .on_hover_text(
        "Aerosol optical depth at 550 nm: how much a vertical beam of green light is dimmed by aerosols alone \
         (by e^−AOD). 0.05 is very clean air, 0.5 a hazy polluted day, above 1 a dust storm.",
    );
    ui.horizontal(|ui| {
        ui.radio_value(&mut a.phase, AerosolPhase::HenyeyGreenstein, "Henyey–Greenstein");
        ui.radio_value(&mut a.phase, AerosolPhase::CornetteShanks, "Cornette–Shanks");
        ui.add_enabled_ui(a.kind != AerosolType::Custom, |ui| {
            ui.radio_value(&mut a.phase, AerosolPhase::Mie, "Mie");
        });
    })
    .response
    .on_hover_text(
        "The angular shape of aerosol scattering: strongly forward, which makes the bright halo around the sun. \
         Mie is the type's own, from the Mie code over its particles' sizes (its forward peak and back-scatter); \
         the other two share only its asymmetry g. The first use of Mie takes a second to compute.",
    );
    if a.kind == AerosolType::Custom && a.phase == AerosolPhase::Mie {
        a.phase = AerosolPhase::HenyeyGreenstein;
    }
    if a.kind == AerosolType::Custom {
        let c = &mut a.custom;
        ui.add(Slider::new(&mut c.single_scattering_albedo, limits::CUSTOM_AEROSOL_SSA.range()).text("single-scattering albedo"))
            .on_hover_text("Share of the light a particle removes that it scatters; the rest it absorbs (1 = no absorption).");
        ui.add(
            Slider::new(&mut c.asymmetry_g, limits::CUSTOM_AEROSOL_G.range()).text("asymmetry g"),
        )
        .on_hover_text(
            "Mean cosine of the scattering angle: 0 scatters evenly, near 1 almost straight ahead.",
        );
        ui.add(Slider::new(&mut c.angstrom_exponent, limits::CUSTOM_AEROSOL_ANGSTROM.range()).text("Ångström exponent"))
            .on_hover_text("How fast extinction falls with wavelength, ∝ λ^−α: about 0 for coarse dust, 1.5–2 for fine smoke.");
        ui.add(
            Slider::new(
                &mut c.scale_height_km,
                limits::CUSTOM_AEROSOL_SCALE_HEIGHT_KM.range(),
            )
            .logarithmic(true)
            .text("scale height (km)"),
        )
        .on_hover_text("Height over which the aerosol density falls by a factor e.");
    }
}

fn ozone(ui: &mut egui::Ui, s: &mut Scene) {
    let sun_by_date = matches!(s.sun, SunSettings::Date { .. });
    let top_m = s.atmosphere.top_km * 1000.0;
    let o = &mut s.atmosphere.ozone;
    let afgl = matches!(o.profile, OzoneProfile::Afgl(_));
    ui.horizontal(|ui| {
        if ui.radio(matches!(o.column, OzoneColumn::Month(_)), "By month").clicked() {
            o.column = OzoneColumn::Month(6);
        }
        if ui.radio(matches!(o.column, OzoneColumn::Zonal { .. }), "Zonal mean").clicked() {
            let month = match o.column {
                OzoneColumn::Month(m) => m,
                _ => 6,
            };
            o.column = OzoneColumn::Zonal {
                latitude_deg: 46.8,
                month,
            };
        }
        if ui.radio(matches!(o.column, OzoneColumn::Du(_)), "Dobson units").clicked() {
            o.column = OzoneColumn::Du(300.0);
        }
        if ui.add_enabled(afgl, egui::RadioButton::new(o.column == OzoneColumn::Profile, "Profile's own")).clicked() {
            o.column = OzoneColumn::Profile;
        }
    })
    .response
    .on_hover_text(
        "The total amount of ozone overhead. Ozone absorbs orange light (the Chappuis band), which keeps the \
         twilight zenith blue. 300 DU would be a 3 mm layer at ground pressure.",
    );
    match &mut o.column {
        OzoneColumn::Month(m) => {
            ui.add(
                Slider::new(m, 1..=12)
                    .custom_formatter(|v, _| MONTHS[(v as usize).clamp(1, 12) - 1].to_string())
                    .text("month"),
            )
            .on_hover_text(
                "Monthly mean ozone at Arosa (47° N): highest in spring, lowest in autumn.",
            );
        }
        OzoneColumn::Du(du) => {
            ui.add(
                Slider::new(du, limits::OZONE_COLUMN_DU.range())
                    .suffix(" DU")
                    .text("column"),
            )
            .on_hover_text(
                "Total ozone column in Dobson units; the Antarctic ozone hole falls below 220 DU.",
            );
        }
        OzoneColumn::Zonal {
            latitude_deg,
            month,
        } => {
            ui.add_enabled_ui(!sun_by_date, |ui| {
                ui.add(
                    Slider::new(latitude_deg, limits::LATITUDE_DEG.range())
                        .suffix("°")
                        .text("latitude"),
                )
                .on_hover_text("Degrees north; the south's seasons run six months behind.");
                ui.add(
                    Slider::new(month, 1..=12)
                        .custom_formatter(|v, _| MONTHS[(v as usize).clamp(1, 12) - 1].to_string())
                        .text("month"),
                );
            })
            .response
            .on_hover_text(if sun_by_date {
                "The sun is placed by date and place: the ozone follows its latitude and month."
            } else {
                "Zonal-mean ozone from the AFGL standard atmospheres (Anderson et al. 1986): tropical \
                 15° N all year, midlatitude 45° N and subarctic 60° N in January and July, between \
                 them by latitude and month; the south takes the north's seasons six months later."
            });
        }
        OzoneColumn::Profile => {}
    }
    ui.label(format!("Total column: {:.0} DU", o.column_du(top_m)));
    ComboBox::from_label("Vertical profile")
        .selected_text(o.profile.cli_name())
        .show_ui(ui, |ui| {
            for p in OzoneProfile::all() {
                ui.selectable_value(&mut o.profile, p, p.cli_name());
            }
        })
        .response
        .on_hover_text(
            "How ozone is spread with height: a layer peaking near 20–25 km in every profile.",
        );
    if o.column == OzoneColumn::Profile && !matches!(o.profile, OzoneProfile::Afgl(_)) {
        o.column = OzoneColumn::Month(6);
    }
    ComboBox::from_label("Cross-section")
        .selected_text(o.cross_section.cli_name())
        .show_ui(ui, |ui| {
            ui.selectable_value(
                &mut o.cross_section,
                OzoneCrossSection::Bogumil2003,
                "bogumil-2003",
            );
            ui.selectable_value(
                &mut o.cross_section,
                OzoneCrossSection::Serdyuchenko233K,
                "serdyuchenko-233k",
            );
        })
        .response
        .on_hover_text(
            "Laboratory measurement of how strongly one ozone molecule absorbs each wavelength.",
        );
    ui.add_enabled(
        o.cross_section == OzoneCrossSection::Bogumil2003,
        Slider::new(&mut o.temperature_k, limits::OZONE_TEMPERATURE_K.range())
            .suffix(" K")
            .text("temperature"),
    )
    .on_hover_text(
        "Ozone absorbs slightly differently when cold; the ozone layer is near 220–240 K.",
    );
}

/// A measured ground's albedo against wavelength over the engine's range, its visible albedo
/// and its source.
fn ground_spectrum(ui: &mut egui::Ui, ground: GroundType) {
    let points: Vec<[f64; 2]> = (360..=830)
        .step_by(5)
        .map(|w| [f64::from(w), ground.albedo(0.0, f64::from(w), None)])
        .collect();
    egui_plot::Plot::new("ground-spectrum")
        .height(90.0)
        .include_y(0.0)
        .include_y(1.0)
        .allow_drag(false)
        .allow_zoom(false)
        .allow_scroll(false)
        .x_axis_label("wavelength (nm)")
        .y_axis_label("albedo")
        .show(ui, |p| {
            p.line(egui_plot::Line::new(
                ground.label(),
                egui_plot::PlotPoints::from(points),
            ))
        });
    if let Some(a) = ground.stated_visible_albedo() {
        ui.label(format!("visible albedo {a:.2} (400–700 nm)"));
    }
    ui.small(ground.source());
}

fn ground_and_air(ui: &mut egui::Ui, s: &mut Scene) {
    let atm = &mut s.atmosphere;
    ComboBox::from_label("Ground")
        .selected_text(atm.ground.label())
        .show_ui(ui, |ui| {
            for g in GroundType::ALL {
                ui.selectable_value(&mut atm.ground, g, g.label());
            }
        })
        .response
        .on_hover_text(
            "The ground's surface. A measured one reflects each wavelength as that surface does, in the ground's colour \
             and in the light it sends back up into the sky: snow brightens the sky from below.",
        );
    if atm.ground == GroundType::Grey {
        ui.add(Slider::new(&mut atm.ground_albedo, limits::GROUND_ALBEDO.range()).text("ground albedo")).on_hover_text(
            "Share of light the grey ground reflects at every wavelength: ocean 0.06, forest 0.15, sand 0.4, fresh snow \
             0.9. A bright ground lights the sky from below.",
        );
    } else {
        ground_spectrum(ui, atm.ground);
    }
    ComboBox::from_label("Air profile")
        .selected_text(atm.air_profile.cli_name())
        .show_ui(ui, |ui| {
            for p in AirProfile::all() {
                ui.selectable_value(&mut atm.air_profile, p, p.cli_name());
            }
        })
        .response
        .on_hover_text(
            "Density of air with height. Air molecules scatter blue light about five times more than red (Rayleigh, ∝ λ^-4), \
             which makes the sky blue.",
        );
    ui.checkbox(&mut atm.rayleigh_depolarisation, "Rayleigh depolarisation")
        .on_hover_text("Air molecules are not perfect spheres: about 3 % depolarisation makes side scattering slightly stronger.");
    ComboBox::from_label("Solar spectrum")
        .selected_text(atm.solar_spectrum.label())
        .show_ui(ui, |ui| {
            for sp in SolarSpectrum::ALL {
                ui.selectable_value(&mut atm.solar_spectrum, sp, sp.label());
            }
        })
        .response
        .on_hover_text("The sun's light above the atmosphere, as measured; the tables differ by a few percent.");
    ui.add(
        Slider::new(&mut atm.planet_radius_km, limits::PLANET_RADIUS_KM.range())
            .logarithmic(true)
            .suffix(" km")
            .text("planet radius"),
    )
    .on_hover_text(
        "Earth's mean radius is 6360 km in sky models; a smaller planet curves the horizon more.",
    );
    ui.add(
        Slider::new(&mut atm.top_km, limits::TOP_KM.range())
            .logarithmic(true)
            .suffix(" km")
            .text("top of atmosphere"),
    )
    .on_hover_text(
        "Height above which the air is ignored; 100 km (the Kármán line) loses nothing visible.",
    );
    ui.add(
        Slider::new(
            &mut atm.air_density_scale,
            limits::AIR_DENSITY_SCALE.range(),
        )
        .logarithmic(true)
        .text("air density ×"),
    )
    .on_hover_text(
        "The air profile's density times this factor at every height: thinner air scatters less blue (Mars' surface air is about 1/60 of Earth's), denser air reddens the whole sky.",
    );
}

fn sun(ui: &mut egui::Ui, s: &mut Scene) {
    let angles = s.sun.angles();
    ui.horizontal(|ui| {
        if ui
            .radio(matches!(s.sun, SunSettings::Angles { .. }), "Angles")
            .clicked()
        {
            s.sun = SunSettings::Angles {
                elevation_deg: angles.elevation_deg,
                azimuth_deg: angles.azimuth_deg,
            };
        }
        if ui
            .radio(
                matches!(s.sun, SunSettings::Date { .. }),
                "Date, time and place",
            )
            .clicked()
            && matches!(s.sun, SunSettings::Angles { .. })
        {
            s.sun = SunSettings::Date {
                time: DateTime {
                    year: 2025,
                    month: 6,
                    day: 21,
                    hour: 12.0,
                    utc_offset_h: 2.0,
                },
                latitude_deg: 47.37,
                longitude_deg: 8.54,
            };
        }
    });
    match &mut s.sun {
        SunSettings::Angles {
            elevation_deg,
            azimuth_deg,
        } => {
            ui.add(Slider::new(elevation_deg, limits::SUN_ELEVATION_DEG.range()).suffix("°").text("elevation")).on_hover_text(
                "Height of the sun above the horizon. Low sun light crosses up to 40 times more air, so blue is scattered \
                 away and the sun turns red; below 0° only the upper air is lit (twilight).",
            );
            ui.add(Slider::new(azimuth_deg, limits::SUN_AZIMUTH_DEG.range()).suffix("°").text("azimuth"))
                .on_hover_text("Compass direction of the sun, clockwise from north (90° east, 180° south, 270° west).");
        }
        SunSettings::Date {
            time,
            latitude_deg,
            longitude_deg,
        } => {
            ui.horizontal(|ui| {
                // A prefix names the value for screen readers as for the eye.
                ui.add(
                    DragValue::new(&mut time.year)
                        .range(limits::DATE_YEAR.range())
                        .prefix("year "),
                );
                ui.add(
                    DragValue::new(&mut time.month)
                        .range(1..=12)
                        .prefix("month "),
                );
                ui.add(
                    DragValue::new(&mut time.day)
                        .range(limits::DATE_DAY.range())
                        .prefix("day "),
                );
            });
            ui.add(Slider::new(&mut time.hour, limits::DATE_HOUR.range()).text("local time (h)"));
            ui.add(
                Slider::new(&mut time.utc_offset_h, limits::DATE_UTC_OFFSET_H.range())
                    .text("UTC offset (h)"),
            );
            ui.add(
                Slider::new(latitude_deg, limits::LATITUDE_DEG.range())
                    .suffix("° N")
                    .text("latitude"),
            )
            .on_hover_text(
                "The sun's path depends on latitude: it never rises far at the poles in winter.",
            );
            ui.add(
                Slider::new(longitude_deg, limits::LONGITUDE_DEG.range())
                    .suffix("° E")
                    .text("longitude"),
            );
            ui.label(format!(
                "sun at elevation {:.2}°, azimuth {:.2}°",
                angles.elevation_deg, angles.azimuth_deg
            ))
            .on_hover_text(
                "Computed with the NOAA solar position equations (geometric, without refraction).",
            );
        }
    }
}

fn camera(ui: &mut egui::Ui, s: &mut Scene) {
    let c = &mut s.camera;
    ui.add(Slider::new(&mut c.altitude_m, limits::CAMERA_ALTITUDE_M.range()).logarithmic(true).smallest_positive(1.0).suffix(" m").text("altitude"))
        .on_hover_text(
            "Camera height above the ground, from 1 m to 100 000 km. Half the air lies below 5.5 km; above 100 km the \
             atmosphere is a thin glowing shell.",
        );
    ui.add(
        Slider::new(&mut c.heading_deg, limits::CAMERA_HEADING_DEG.range())
            .suffix("°")
            .text("heading"),
    )
    .on_hover_text("Compass direction the camera looks, clockwise from north.");
    ui.add(
        Slider::new(&mut c.pitch_deg, limits::CAMERA_PITCH_DEG.range())
            .suffix("°")
            .text("pitch"),
    )
    .on_hover_text("How far the camera looks above (+) or below (−) the horizon.");
    ui.add(
        Slider::new(&mut c.fov_deg, limits::CAMERA_FOV_DEG.range())
            .suffix("°")
            .text("field of view"),
    )
    .on_hover_text("Vertical angle the image covers; the eye's comfortable field is about 60°.");
    ui.add(
        Slider::new(&mut c.back_km, limits::CAMERA_BACK_KM.range())
            .logarithmic(true)
            .suffix(" km")
            .text("moved back"),
    )
    .on_hover_text(
        "Moves the camera back over the curved planet, against its heading, keeping its altitude: from \
         orbit this shows the sunlit limb ahead. The sun stays where it is in the sky of the scene's origin.",
    );
    polariser(ui, c);
}

/// The camera's polarising filter: on or off, and the angle of its transmission axis.
fn polariser(ui: &mut egui::Ui, c: &mut atmoscope_model::scene::CameraSettings) {
    // The angle stays in the widget's memory while the filter is off.
    let id = egui::Id::unique("polariser angle");
    let mut angle = c
        .polariser_deg
        .unwrap_or_else(|| ui.ctx().data(|d| d.get_temp(id)).unwrap_or(0.0));
    let mut on = c.polariser_deg.is_some();
    ui.checkbox(&mut on, "polarising filter").on_hover_text(
        "A linear polariser in front of the lens, as a photographer's circular polariser acts on the \
         sky: it passes (I + Q cos 2θ + U sin 2θ)/2 of the light, in every view and export. Turned \
         across the electric vector, 90° from the sun, it darkens the blue sky; towards the sun it \
         changes little. It passes half of unpolarised light (one stop), which metered exposure \
         makes up. The sky's polarisation is the Polarisation tab's; aerosols add unpolarised light.",
    );
    ui.add_enabled(
        on,
        Slider::new(&mut angle, limits::CAMERA_POLARISER_DEG.range())
            .suffix("°")
            .text("filter angle"),
    )
    .on_hover_text(
        "The filter's transmission axis, from up in the picture towards right: 0° passes light vibrating \
         vertically, ±90° horizontally.",
    );
    ui.ctx().data_mut(|d| d.insert_temp(id, angle));
    c.polariser_deg = on.then_some(angle);
}

/// What a model does, where it is valid and where it comes from.
fn model_tooltip(m: &methods::ModelInfo) -> String {
    let aod = if m.domain.max_aod550.is_finite() {
        format!("; AOD up to {:.2}", m.domain.max_aod550)
    } else {
        String::new()
    };
    format!(
        "{}: {}\nDomain: {} ({}){aod}.\n{}",
        m.label,
        m.summary,
        m.domain.kinds().join(", "),
        m.domain.note,
        m.citation
    )
}

/// The CIE standard general sky's type, and what the model is not: it has no spectrum.
fn cie_sky_type(ui: &mut egui::Ui, r: &mut atmoscope_model::scene::RenderSettings) {
    let current = cie_standard_sky::sky_type(r.cie_sky_type);
    ComboBox::from_label("CIE sky type")
        .selected_text(format!("{}: {}", current.number, current.description))
        .width(220.0)
        .show_ui(ui, |ui| {
            for t in cie_standard_sky::types() {
                ui.selectable_value(
                    &mut r.cie_sky_type,
                    t.number,
                    format!("{}: {}", t.number, t.description),
                )
                .on_hover_text(format!(
                    "Gradation group {} (a = {}, b = {}), indicatrix group {} (c = {}, d = {}, e = {}){}",
                    t.gradation_group,
                    t.a,
                    t.b,
                    t.indicatrix_group,
                    t.c,
                    t.d,
                    t.e,
                    if t.sun { "; the sun shows" } else { "; the sun is hidden" }
                ));
            }
        })
        .response
        .on_hover_text(
            "The 15 relative luminance distributions of CIE S 011 / ISO 15469, from the overcast sky (1) to the \
             turbid clear sky (15); 12 is the CIE standard clear sky.",
        );
    ui.label(
        egui::RichText::new(
            "A luminance model: it has no spectrum. Its colour is the sun's white, the same in every \
             direction; its zenith luminance is Preetham's formula at the scene's turbidity.",
        )
        .small()
        .weak(),
    );
}

fn render(ui: &mut egui::Ui, s: &mut Scene, meter: Option<&exposure::Reading>) {
    let r = &mut s.render;
    let current = methods::info(r.method);
    ComboBox::from_label("Method")
        .selected_text(current.label)
        .show_ui(ui, |ui| {
            for m in methods::realtime() {
                ui.selectable_value(&mut r.method, m.method, m.label)
                    .on_hover_text(model_tooltip(m));
            }
        })
        .response
        .on_hover_text(format!(
            "The sky model that draws the views. {}\n\nThe path tracer, the ground truth every model is measured against, renders in the Reference tab.",
            model_tooltip(current)
        ));
    if current.gathers_orders {
        ui.add(
            Slider::new(&mut r.scattering_orders, {
                let l = limits::SCATTERING_ORDERS;
                l.min as u32..=l.max as u32
            })
            .text("scattering orders"),
        )
        .on_hover_text(
            "How many orders of scattering the model gathers one by one when it builds its tables: 1 is single \
             scattering only; each order costs one more pass of every table. Bruneton's reference uses 4; \
             the default is 6, since a hazy sky still gains a tenth of its blue near the horizon past the fourth.",
        );
    }
    if current.refittable {
        ComboBox::from_label("fitted constants")
            .selected_text(match r.fitted_constants {
                FittedConstants::Published => "published",
                FittedConstants::Refit => "refit",
            })
            .show_ui(ui, |ui| {
                ui.selectable_value(&mut r.fitted_constants, FittedConstants::Published, "published");
                ui.selectable_value(&mut r.fitted_constants, FittedConstants::Refit, "refit");
            })
            .response
            .on_hover_text(
                "The model's fitted constants (García Liñán's multiple-scattering fit L_ms): as the author published \
                 them (fitted at 10 km), or this project's refit against the path tracer over the suite's daylight \
                 views (`atmoscope fit-garcia-linan`).",
            );
    }
    if r.method == Method::CieStandardSky {
        cie_sky_type(ui, r);
    }
    ComboBox::from_label("Wavelengths")
        .selected_text(r.wavelengths.label())
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut r.wavelengths, WavelengthSet::Rgb3, "RGB3");
            ui.selectable_value(&mut r.wavelengths, WavelengthSet::Spectral4, "Spectral4");
            ui.selectable_value(&mut r.wavelengths, WavelengthSet::SpectralN(32), "SpectralN");
        })
        .response
        .on_hover_text(
            "RGB3 treats 680/550/440 nm as red, green and blue (fast, biased); Spectral4 maps four wavelengths to colour \
             with a fitted matrix; SpectralN integrates N wavelengths against the eye's colour matching functions.",
        );
    if let WavelengthSet::SpectralN(n) = &mut r.wavelengths {
        ui.add(Slider::new(n, 4..=128).step_by(4.0).text("N"));
    }
    ComboBox::from_label("Quality")
        .selected_text(format!("{:?}", r.quality))
        .show_ui(ui, |ui| {
            for q in [Quality::Low, Quality::Medium, Quality::High] {
                ui.selectable_value(&mut r.quality, q, format!("{q:?}"));
            }
        })
        .response
        .on_hover_text(
            "Ray-marching sample counts of the model's passes (×1, ×2, ×4 from Low to High): higher is more accurate and slower. Table sizes stay the same.",
        );
    let d = &mut s.display;
    ui.checkbox(&mut d.auto_exposure, "Automatic exposure").on_hover_text(
        "Meter the view like a camera: the exposure that shows its average (log) luminance as mid-grey, reached over about half a second. Off: the exposure below, fixed (what comparisons and teaching want).",
    );
    ui.add_enabled(
        !d.auto_exposure,
        Slider::new(&mut d.exposure_ev, limits::EXPOSURE_EV.range())
            .suffix(" EV")
            .text("exposure"),
    )
    .on_hover_text(
        "Brightness of the display in photographic stops: +1 doubles it. Twilight needs +5 to +10.",
    );
    if d.auto_exposure {
        ui.add(
            Slider::new(&mut d.compensation_ev, limits::COMPENSATION_EV.range())
                .suffix(" EV")
                .text("compensation"),
        )
        .on_hover_text("Brighter (+) or darker (−) than the metered exposure, in stops.");
        if let Some(m) = meter {
            ui.label(format!(
                "metered: {:.3} cd/m² (log-average), EV100 {:.1}",
                m.log_average_cd_m2, m.ev100
            ))
            .on_hover_text("EV100: the exposure value a reflected-light meter at ISO 100 gives for this view (15 is a sunlit scene, about 2 deep dusk).");
            exposure::show_histogram(ui, &m.histogram);
        }
    }
    ComboBox::from_label("Tone map")
        .selected_text(d.tone_map.label())
        .show_ui(ui, |ui| {
            for t in ToneMap::ALL {
                ui.selectable_value(&mut d.tone_map, t, t.label())
                    .on_hover_text(t.describe());
            }
        })
        .response
        .on_hover_text(format!(
            "How the sky's huge range of brightness is squeezed into what a screen can show. {}",
            d.tone_map.describe()
        ));
    let kelvin = match d.white_balance {
        WhiteBalance::Temperature { kelvin } => kelvin,
        _ => 5000.0,
    };
    let label = |w: WhiteBalance| match w {
        WhiteBalance::None => "None (D65)".to_string(),
        WhiteBalance::SunAtNoon => "The sun at noon".to_string(),
        WhiteBalance::Temperature { kelvin } => format!("{kelvin:.0} K"),
    };
    ComboBox::from_label("White balance")
        .selected_text(label(d.white_balance))
        .show_ui(ui, |ui| {
            ui.selectable_value(&mut d.white_balance, WhiteBalance::None, "None (D65)")
                .on_hover_text("Colours as measured: the sRGB white, D65, is white.");
            ui.selectable_value(&mut d.white_balance, WhiteBalance::SunAtNoon, "The sun at noon")
                .on_hover_text("The sun's direct light at the ground when overhead, through this atmosphere, is white, as a camera set to daylight sees.");
            ui.selectable_value(
                &mut d.white_balance,
                WhiteBalance::Temperature { kelvin },
                "Colour temperature",
            )
            .on_hover_text("A blackbody at the chosen temperature is white: lower makes the picture bluer, higher warmer.");
        })
        .response
        .on_hover_text("Which light the display shows as white, by a chromatic adaptation transform (Bradford).");
    if let WhiteBalance::Temperature { kelvin } = &mut d.white_balance {
        let k = limits::WHITE_BALANCE_KELVIN;
        ui.add(
            Slider::new(kelvin, k.min..=k.max)
                .logarithmic(true)
                .suffix(" K")
                .text("colour temperature"),
        );
    }
    ui.checkbox(&mut d.dither, "Dither")
        .on_hover_text("Adds up to one step of noise per pixel to the 8-bit image so that smooth skies do not band. Off for byte-exact comparisons.");
    ui.checkbox(&mut d.glare, "Glare around the sun")
        .on_hover_text("Adds the eye's veiling glare around the sun to the picture (10·E/θ², the Stiles–Holladay law: E the sun's irradiance here, θ degrees from it). A display effect: the radiance, the inspector, exports as EXR and every measurement stay without. Off for measurement.");
}
