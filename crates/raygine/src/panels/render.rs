//! Render settings (restart the render) and display settings (re-map only).

use tracer_core::display::{
    DisplaySettings, FalseColour, FalseColourQuantity, FalseColourScale, ToneMap,
};
use tracer_core::integrator::IntegratorKind;
use tracer_core::scene::Projection;

/// Render preferences that restart the render when changed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RenderPrefs {
    /// Light transport: global illumination by default in the viewer.
    pub integrator: IntegratorKind,
    pub max_depth: u32,
    pub target_spp: u32,
    /// After 16 samples in every pixel, the rest of the target's samples go where the error is
    /// highest.
    pub adaptive: bool,
    /// Film pixels per screen pixel (0.25 ..= 1).
    pub resolution_scale: f32,
    pub threads: usize,
}

/// The false-colour view as edited in the panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FalseColourUi {
    pub enabled: bool,
    pub quantity: FalseColourQuantity,
    pub scale: FalseColourScale,
    pub min: f32,
    pub max: f32,
}

impl Default for FalseColourUi {
    fn default() -> Self {
        Self {
            enabled: false,
            quantity: FalseColourQuantity::Illuminance,
            scale: FalseColourScale::Log,
            min: 1.0,
            max: 10_000.0,
        }
    }
}

impl FalseColourUi {
    /// `display` with this false-colour view over it (when enabled).
    pub fn over(&self, display: &DisplaySettings) -> DisplaySettings {
        DisplaySettings {
            false_colour: self.enabled.then_some(FalseColour {
                quantity: self.quantity,
                scale: self.scale,
                min: self.min,
                max: self.max,
            }),
            ..*display
        }
    }
}

/// The render settings, the display settings and the false-colour view, edited in place.
/// `projection` is the camera's: an integrator that cannot render it is disabled.
pub fn render_ui(
    ui: &mut egui::Ui,
    projection: Projection,
    r: &mut RenderPrefs,
    d: &mut DisplaySettings,
    fc: &mut FalseColourUi,
) {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    egui::ComboBox::from_label("light transport")
        .selected_text(r.integrator.label())
        .show_ui(ui, |ui| {
            for k in IntegratorKind::ALL {
                let refused = k.check_projection(projection).err();
                super::widgets::refusable_choice(ui, &mut r.integrator, k, k.label(), refused);
            }
        })
        .response
        .on_hover_text(
            "Global illumination: all light, reflected any number of times, unbiased. \
             Bidirectional traces paths from the lights too (best for lamps close to \
             surfaces, glass and caustics); path traces from the camera only. Direct: the \
             coursework's model, direct light and mirrors only.",
        );
    ui.add_enabled(
        r.integrator == IntegratorKind::Direct,
        egui::Slider::new(&mut r.max_depth, 0..=16).text("max reflection depth"),
    )
    .on_hover_text("Direct mode: mirror bounces traced after the camera ray");
    ui.add(
        egui::Slider::new(&mut r.target_spp, 1..=4096)
            .logarithmic(true)
            .text("samples target (spp)"),
    )
    .on_hover_text(
        "Rendering stops (and uses no CPU) once the picture has this many samples per pixel \
         on average",
    );
    ui.checkbox(&mut r.adaptive, "adaptive sampling")
        .on_hover_text(
            "After 16 samples in every pixel, the rest of the target goes where the relative \
         error is highest (predicted from each pixel's neighbours, so means stay unbiased). \
         Off: every pixel gets the target.",
        );
    ui.add(egui::Slider::new(&mut r.resolution_scale, 0.25..=1.0).text("resolution scale"))
        .on_hover_text("Film pixels per screen pixel: lower is faster while you explore");
    ui.add(egui::Slider::new(&mut r.threads, 1..=cores.max(1)).text("render threads"));
    ui.separator();
    ui.horizontal(|ui| {
        ui.add_enabled(
            !d.auto_exposure,
            egui::Slider::new(&mut d.exposure_stops, -12.0..=12.0).text("exposure (stops)"),
        )
        .on_hover_text(
            "0 stops: 100 cd/m² is display white; +1 doubles. Kept per scene: set on a scene's \
             first view (its median surface to middle grey), yours once you move it",
        );
    });
    ui.checkbox(&mut d.auto_exposure, "auto exposure")
        .on_hover_text(
            "Follows the picture pass by pass: its log-average luminance maps to middle grey",
        );
    egui::ComboBox::from_label("tone mapping")
        .selected_text(d.tone_map.name())
        .show_ui(ui, |ui| {
            for t in ToneMap::ALL {
                ui.selectable_value(&mut d.tone_map, t, t.name());
            }
        });
    ui.checkbox(&mut fc.enabled, "false colour");
    ui.add_enabled_ui(fc.enabled, |ui| {
        ui.horizontal(|ui| {
            ui.selectable_value(
                &mut fc.quantity,
                FalseColourQuantity::Luminance,
                "luminance (cd/m²)",
            );
            ui.selectable_value(
                &mut fc.quantity,
                FalseColourQuantity::Illuminance,
                "illuminance (lx)",
            );
        });
        ui.horizontal(|ui| {
            ui.selectable_value(&mut fc.scale, FalseColourScale::Log, "log");
            ui.selectable_value(&mut fc.scale, FalseColourScale::Linear, "linear");
        });
        let unit = fc.quantity.unit();
        ui.horizontal(|ui| {
            ui.label(format!("range ({unit})"));
            ui.add(
                egui::DragValue::new(&mut fc.min)
                    .speed(0.1)
                    .range(0.0..=f32::MAX),
            )
            .on_hover_text(format!("false colour: value of the lowest colour ({unit})"));
            ui.add(
                egui::DragValue::new(&mut fc.max)
                    .speed(1.0)
                    .range(0.0..=f32::MAX),
            )
            .on_hover_text(format!(
                "false colour: value of the highest colour ({unit})"
            ));
        });
        if fc.max <= fc.min {
            fc.max = fc.min * 10.0 + 1.0;
        }
        if fc.scale == FalseColourScale::Log && fc.min <= 0.0 {
            fc.min = 0.01;
        }
    });
}

/// The "Denoise" toggle (D): on by default in the GI modes, off in Direct; disabled, with the
/// reason, without Open Image Denoise.
pub fn denoise_ui(
    ui: &mut egui::Ui,
    dn: &mut crate::denoise_view::DenoiseView,
    mode: IntegratorKind,
    false_colour: bool,
) {
    use crate::denoise_view::Availability;
    let mut on = dn.wanted(mode) && dn.available();
    let response = ui.add_enabled(dn.available(), egui::Checkbox::new(&mut on, "denoise (D)"));
    if response.changed() {
        dn.toggle(mode);
    }
    match &dn.availability {
        Availability::Loading => {
            ui.weak("denoiser: loading Open Image Denoise…");
        }
        Availability::Unavailable(why) => {
            ui.weak(format!("denoise unavailable: {why}"));
        }
        Availability::Ready(version) => {
            response.on_hover_text(format!(
                "Shows the picture denoised by {version} (albedo and normal guides). \
                 Readouts (hover, meter, grids, noise) stay on the unbiased sums."
            ));
            if false_colour && on {
                ui.weak("false colour shows the raw values");
            }
        }
    }
}
