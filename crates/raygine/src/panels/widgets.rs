//! Number widgets the panels share: lengths dragged at a speed scaled to the scene, with fine
//! control under Shift (egui's drag values move a tenth as fast while Shift is held).

use tracer_core::geometry::Aabb;

/// A length's drag speed, scene units per point dragged: a 400th of the bounds' largest side
/// (1.4 mm a point in the 556 mm box, 12 mm in a 5 m room), 1/10 of that with Shift.
pub fn length_speed(bounds: &Aabb) -> f64 {
    f64::from(bounds.extent().max_element().max(1e-3)) / 400.0
}

/// A number dragged at `speed` a point (Shift: a tenth) or typed, shown with `prefix`, and named
/// `name` for screen readers and tests. A drag that starts inside `keep_in` stays inside it; a
/// typed value may go anywhere.
pub fn fine_drag(
    ui: &mut egui::Ui,
    value: &mut f32,
    speed: f64,
    keep_in: Option<std::ops::RangeInclusive<f32>>,
    prefix: &str,
    name: &str,
) -> egui::Response {
    let before = *value;
    let response = ui.add(
        egui::DragValue::new(value)
            .speed(speed)
            .prefix(prefix)
            .max_decimals(3)
            .update_while_editing(false),
    );
    if let Some(range) = keep_in
        && response.dragged()
        && range.contains(&before)
    {
        *value = value.clamp(*range.start(), *range.end());
    }
    let shown = f64::from(*value);
    let name = name.to_owned();
    response.widget_info(move || {
        let mut info = egui::WidgetInfo::drag_value(true, shown);
        info.label = Some(name.clone());
        info
    });
    response
}

/// Hover text for a dragged length: how far a point moves it, in `unit`.
pub fn drag_hint(speed: f64, unit: &str) -> String {
    format!(
        "drag: {} {unit} a point, with Shift {} {unit}; or double-click and type",
        crate::format::format_value(speed as f32),
        crate::format::format_value(speed as f32 / 10.0)
    )
}

/// A menu entry for `value`: selected when `*current` is it, disabled with the reason on hover
/// when `refused` says why it cannot be chosen; a click chooses it.
pub fn refusable_choice<T: PartialEq + Copy>(
    ui: &mut egui::Ui,
    current: &mut T,
    value: T,
    label: &str,
    refused: Option<String>,
) {
    let item = ui.add_enabled(
        refused.is_none(),
        egui::Button::selectable(*current == value, label),
    );
    let item = match refused {
        Some(why) => item.on_disabled_hover_text(why),
        None => item,
    };
    if item.clicked() {
        *current = value;
    }
}
