//! A reflectance colour: the sRGB picker, and beside it the numbers (0-1 per channel, linear, as
//! the renderer uses them) or one grey value for all three.

/// Draws the picker and the numbers for `rgb` (linear reflectance per channel, 0..=1).
pub fn reflectance_ui(ui: &mut egui::Ui, name: &str, description: &str, rgb: &mut [f32; 3]) {
    ui.horizontal(|ui| {
        ui.color_edit_button_rgb(rgb)
            .on_hover_text(format!("{name}: pick the colour (sRGB picker)"));
        ui.label(description);
    });
    ui.horizontal(|ui| {
        ui.add_space(8.0);
        let grey_label = ui.label("grey");
        let mut grey = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
        let grey_changed = ui
            .add(number(&mut grey))
            .labelled_by(grey_label.id)
            .on_hover_text(format!(
                "{name}: one reflectance for all three channels (shows their mean)"
            ))
            .changed();
        if grey_changed {
            *rgb = [grey; 3];
        }
        let channels = ui.label("or");
        for (c, prefix) in ["R ", "G ", "B "].iter().enumerate() {
            ui.add(number(&mut rgb[c]).prefix(*prefix))
                .labelled_by(channels.id)
                .on_hover_text(format!(
                    "{name}: reflectance of the {} channel, 0-1 (linear)",
                    ["red", "green", "blue"][c]
                ));
        }
    });
}

fn number(value: &mut f32) -> egui::DragValue<'_> {
    egui::DragValue::new(value)
        .speed(0.002)
        .range(0.0..=1.0)
        .fixed_decimals(3)
        .update_while_editing(false)
}
