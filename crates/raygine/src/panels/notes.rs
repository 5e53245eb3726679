//! The Notes window: every warning the open scene's files gave when read, in full, with the
//! file and line each names, so a desktop user without a terminal can read them all.

/// The notes of the open scene; `open` is the window's flag (View > Notes).
pub fn notes_ui(ctx: &egui::Context, open: &mut bool, scene: &str, notes: &[String]) {
    egui::Window::new("Notes on this scene")
        .open(open)
        .default_width(560.0)
        .vscroll(true)
        .show(ctx, |ui| {
            ui.label(format!("{scene}: {}", count(notes.len())));
            ui.separator();
            for (i, note) in notes.iter().enumerate() {
                ui.horizontal_wrapped(|ui| {
                    ui.monospace(format!("{:>3}.", i + 1));
                    ui.add(egui::Label::new(note.as_str()).wrap().selectable(true));
                });
            }
            if !notes.is_empty() && ui.button("Copy all").clicked() {
                ui.ctx().copy_text(notes.join("\n"));
            }
        });
}

/// "no notes", "1 note", "5 notes".
pub fn count(n: usize) -> String {
    match n {
        0 => "no notes: the files read cleanly".to_owned(),
        1 => "1 note".to_owned(),
        n => format!("{n} notes"),
    }
}
